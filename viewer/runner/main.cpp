// springlab-run: the headless front end. Runs a scene with the reference or the student's code
// and writes the state as CSV. Exit codes: 0 done, 1 the code under test failed in a way the kit
// does not know, 2 bad input, 3 diverged, 4 task not written yet, 6 the output could not be
// written (a full disk, a closed pipe: the run stops rather than lose rows without a word).
#include "runner/csv.hpp"
#include "runner/system.hpp"
#include "springlab/cli_values.hpp"
#include "springlab/comparison.hpp"
#include "springlab/errors.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/implementation.hpp"
#include "springlab/integrator.hpp"
#include "springlab/memory_budget.hpp"
#include "springlab/parallel.hpp"
#include "springlab/progress.hpp"
#include "springlab/scene.hpp"
#include "springlab/scene_text.hpp"
#include "springlab/simulation.hpp"
#include "springlab/stability.hpp"

#include <CLI/CLI.hpp>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace {

using namespace springlab;

enum Exit { done = 0, failed = 1, bad_input = 2, diverged = 3, not_written = 4, lost_output = 6 };

// The numbers are kept as written and read by option_number: CLI11 would take "nan", and take
// an empty value for the default.
struct Options {
  std::string scene = "task1";
  std::string impl = "reference";
  std::optional<std::string> integrator;
  std::optional<std::string> dt, duration;
  std::vector<std::string> sets;
  std::optional<std::string> every;  // only with --csv
  std::optional<std::string> csv;    // empty when not given; "" given is an error
  bool quiet = false;
  bool stability = false;
  bool estimate = false;
};

SceneParameters scene_from(const Options& options) {
  if (options.impl != "reference" && options.impl != "student")
    throw InvalidParameter("--impl", quoted_for_terminal(options.impl), "reference or student");
  refuse_double_settings(options.sets, {{"--integrator", "integrator", bool(options.integrator)},
                                        {"--dt", "step", bool(options.dt)},
                                        {"--duration", "duration", bool(options.duration)}});
  SceneParameters p = load_scene(options.scene);
  if (options.integrator) set_parameter(p, "integrator", *options.integrator);
  if (options.dt)
    set_number(p, "step", option_number("--dt", *options.dt, parameter_range("step"), "s"));
  if (options.duration)
    set_number(p, "duration",
               option_number("--duration", *options.duration, parameter_range("duration"), "s"));
  for (const std::string& assignment : options.sets)
    set_assignment(p, assignment);
  validate(p);
  return p;
}

const Implementation& implementation_for(const Options& options, const SceneParameters& p) {
  if (options.impl == "reference") return reference_implementation();
  if (p.task < 1 || p.task > 5)
    throw InvalidParameter("--impl student",
                           "scene \"" + p.name + "\" (task = " + std::to_string(p.task) + ")",
                           "a scene of task 1-5: the student's code of that task runs; in a scene "
                           "file, set task = N");
  return student_implementation(p.task);
}

// Every key --set takes, with its unit, meaning and default (the lab's values).
std::string parameter_list() {
  std::ostringstream out;
  out << "Keys for --set KEY=VALUE and scene files (defaults: the lab's values, scene task1):\n";
  const SceneParameters defaults;
  for_each_field(defaults, [&](const FieldInfo& info, const auto& value) {
    std::ostringstream key;
    key << info.key << (info.unit.empty() ? "" : " [") << info.unit
        << (info.unit.empty() ? "" : "]");
    out << "  " << std::left << std::setw(32) << key.str() << info.meaning << " (" << std::boolalpha
        << value << ")\n";
  });
  return out.str();
}

using runner::peak_resident_mib;

std::string counted(std::size_t n, const std::string& thing) {
  return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}

std::string code_name(const Implementation& impl) {
  if (impl.student_task == 0) return "the reference";
  const std::string task = std::to_string(impl.student_task);
  return "your task " + task + " code (tasks/task" + task + "_*), the reference for the rest";
}

long steps_for(const SceneParameters& p) {
  // Whole steps: the run ends at the first step at or after `duration` (validate() has capped
  // duration/step, so the count fits).
  return long(std::ceil(p.duration / p.step - 1e-9));
}

// ", 0.61 x real time (forces on 2 threads)": simulated seconds per second of wall time, and the
// threads the force code used (OMP_NUM_THREADS; one below the fast path's parallel size).
std::string real_time(const Simulation& sim, double seconds) {
  if (!(seconds > 0.0)) return "";
  const bool parallel =
      sim.fast_forces() && sim.particles().size() >= GridForces::parallel_particles;
  const int threads = parallel ? thread_count() : 1;
  std::ostringstream text;
  text << ", " << std::setprecision(3) << sim.time() / seconds << " x real time (forces on "
       << counted(std::size_t(threads), "thread");
  // More threads asked for than the kit uses: said, not silently ignored.
  const char* asked = std::getenv("OMP_NUM_THREADS");
  if (parallel && asked != nullptr && std::atol(asked) > max_threads())
    text << "; OMP_NUM_THREADS=" << std::atol(asked) << " asks for more than the kit uses, "
         << max_threads() << " (four per processor)";
  text << ")";
  return text.str();
}

// XPBD calls no a(r, v): what it did instead, as a line of the summary.
std::string xpbd_work(const Simulation& sim) {
  const SceneParameters& p = sim.parameters();
  const SolverWork work = sim.integrator().solver_work();
  std::ostringstream text;
  text << "xpbd: " << p.xpbd.substeps << " substeps of " << p.xpbd.iterations
       << (p.xpbd.iterations == 1 ? " iteration" : " iterations") << " a step: " << work.projections
       << " constraint projections, " << work.external << " evaluations of the external forces\n";
  return text.str();
}

void print_summary(std::ostream& out, const Simulation& sim, const Diagnostics& start,
                   double seconds) {
  const Diagnostics end = sim.diagnostics();
  const SceneParameters& p = sim.parameters();
  const bool factorised = sim.integrator().solver_work().factorisations > 0;
  out << "scene " << printable(p.name) << ": " << p.rows << "x" << p.cols << " grid, "
      << counted(sim.particles().size(), "particle") << ", "
      << counted(sim.scene().springs.size(), "spring") << "\n"
      << "code: " << code_name(sim.implementation()) << "; integrator " << p.integrator
      << ", h = " << p.step << " s, " << counted(std::size_t(sim.steps_taken()), "step")
      << " to t = " << sim.time() << " s\n"
      << (p.integrator == "xpbd" ? xpbd_work(sim) : "") << "energy " << start.total() << " J -> "
      << end.total() << " J (" << energy_parts(end, p.gravity.enabled) << "); momentum ("
      << end.momentum.x() << ", " << end.momentum.y() << ") kg*m/s\n"
      << sim.force_evaluations() << " force evaluations in " << seconds << " s of wall time"
      << real_time(sim, seconds) << "\n"
      << "memory: " << peak_resident_mib() << " MiB at most in use (resident), "
      << mebibytes_text(estimated_bytes(p)) << " estimated before the run"
      << (factorised ? " (without the factorisation implicit-euler's fallback made)" : "") << '\n';
}

// The step limit of the run's method on its scene, from the linearised equations at rest.
void print_stability(std::ostream& out, const SceneParameters& p) {
  if (p.rows * p.cols > exact_particles_max) return;  // dense eigen-solves: small scenes only
  const LinearModel model = linearise_at_rest(p, reference_implementation());
  const double limit = critical_step_of(model, p.integrator, p.xpbd.substeps).step;
  if (limit == 0.0) {
    out << "stability: " << p.integrator << " is unstable on this scene at every h (a mode has "
        << "no damping)\n";
    return;
  }
  if (std::isinf(limit)) {
    out << "stability: " << p.integrator << " is stable on this scene at every h\n";
    return;
  }
  out << "stability: " << p.integrator << " is stable on this scene for h < "
      << number_apart(limit, p.step) << " s; ";
  if (p.step < limit) {
    out << "h = " << number_apart(p.step, limit) << " s is within it\n";
    return;
  }
  out << "h = " << number_apart(p.step, limit) << " s is BEYOND it";
  if (p.integrator == "explicit-euler")
    out << ": small motions grow x"
        << number_apart(explicit_euler_growth_factor(model, p.step), 1.0) << " a step";
  out << '\n';
}

// Your code's run beside the reference's on the same scene and steps: the figures, and a remark
// when they differ by more than rounding (comparison.hpp).
void print_comparison(std::ostream& out, const Simulation& sim, const Diagnostics& start) {
  if (!reference_is_available()) return;
  const std::optional<Comparison> c = compare_with_reference(
      sim.parameters(), record_of(sim, start.total()), reference_implementation());
  if (!c) return;
  out << "reference: the same run with the reference's code: yours " << comparison_figures(*c)
      << '\n';
  if (!c->remark.empty()) out << "remark: " << c->remark << '\n';
}

std::string_view how(LimitSource source) {
  switch (source) {
    case LimitSource::exact_formula:
      return "exact (formula)";
    case LimitSource::bisection:
      return "exact (bisection)";
    case LimitSource::modal_estimate:
      return "estimate";
    case LimitSource::lower_bound:
      return "lower bound (2/bound)";
    case LimitSource::no_limit:
      return "no limit";
    case LimitSource::not_computed:
      break;
  }
  return "not computed: needs each mode's damping (an eigen-solve)";
}

// --stability: ω_max and the critical step of every method for the scene, linearised at rest.
void print_stability_report(std::ostream& out, const SceneParameters& p,
                            const Implementation& impl) {
  const StabilityReport report = stability_report(p, impl);
  out << "stability of scene " << printable(p.name) << " (" << p.rows << "x" << p.cols << " grid, "
      << report.particles << " particles), linearised at rest:\n";
  out << "  omega_max";
  if (report.exact) out << " = " << report.frequency << " rad/s (eigen-solve);";
  out << " bound " << report.frequency_bound << " rad/s (Gershgorin row sums of K/m)\n";
  if (!report.exact)
    out << "  (more than " << exact_particles_max
        << " particles: no eigen-solves; the steps below are estimates from the bounds, and "
           "verlet's is a lower bound: the exact 2/omega_max is larger)\n";
  out << "  critical step h_c of each integrator, against h = " << p.step << " s:\n";
  // Each column padded to its width and always followed by two spaces: a value wider than its
  // column (1e+154 s) pushes the rest right instead of running into it.
  const auto column = [](std::string_view text, std::size_t width) {
    std::string padded(text);
    if (padded.size() < width) padded.resize(width, ' ');
    return padded + "  ";
  };
  for (const auto& [name, limit] : report.limits) {
    std::ostringstream value;
    if (limit.source == LimitSource::no_limit || std::isinf(limit.step))
      value << "none";
    else if (limit.source != LimitSource::not_computed)
      value << std::setprecision(6) << limit.step << " s";
    else
      value << "?";
    std::ostringstream line;
    line << "    " << column(name, 16) << column(value.str(), 14) << column(how(limit.source), 20);
    const bool known = limit.source != LimitSource::not_computed;
    if (known && p.step >= limit.step) line << "  h EXCEEDS it: unstable";
    if (name == p.integrator) line << "  <- the scene's integrator";
    std::string text = line.str();
    text.erase(text.find_last_not_of(' ') + 1);
    out << text << '\n';
  }
  out << "  xpbd (" << p.xpbd.substeps << " substeps of " << p.xpbd.iterations << " iteration"
      << (p.xpbd.iterations == 1 ? "" : "s")
      << "): converged, each substep is backward Euler on the springs and dampers, so they set "
         "no limit; only an explicit drag does (h < substeps * 2 m / c). What few substeps or "
         "iterations cost is accuracy: stiff springs stay stretched (./lab tradeoff)\n";
  if (p.wind.enabled && p.wind.drag > 0)
    out << "  the wind's drag c (w - v) is explicit in every integrator (implicit-euler and "
           "velocity-verlet too: only their springs and dampers are implicit); alone it allows "
           "h < 2 m / c = 2 * "
        << p.mass << " kg / " << p.wind.drag << " N*s/m = " << 2 * p.mass / p.wind.drag << " s\n";
}

// Options that would do nothing are refused rather than ignored: the user meant something.
void refuse_idle_options(const Options& options) {
  if (options.every && !options.csv)
    throw InvalidParameter("--every", quoted_for_terminal(*options.every),
                           "only with --csv: it chooses which steps the CSV gets");
  if (options.csv && (options.stability || options.estimate))
    throw InvalidParameter("--csv", quoted_for_terminal(*options.csv),
                           std::string("not with ") +
                               (options.stability ? "--stability" : "--estimate") +
                               ", which runs no steps to write");
}

long every_from(const Options& options) {
  const Range whole_steps{1, max_steps, false, false, true};
  return options.every ? long(option_number("--every", *options.every, whole_steps)) : 1;
}

// --csv naming the scene file (by any path to it) would overwrite the scene: refused before
// anything is opened.
void refuse_the_scene_file(const Options& options) {
  std::error_code error;
  if (!options.csv) return;
  refuse_empty_path("--csv", *options.csv);
  if (*options.csv != "-" && std::filesystem::equivalent(*options.csv, options.scene, error))
    throw InvalidParameter(
        "--csv", quoted_for_terminal(*options.csv),
        "not the scene file: writing the CSV would overwrite the scene " + options.scene);
}

// --estimate: the first steps timed (wall time), the whole run's time from them.
int print_estimate(Simulation& sim, long steps) {
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  long n = 0;
  while (n < steps && (n == 0 || elapsed() < 0.2)) {
    sim.step();
    ++n;
  }
  const double per_step = n > 0 ? elapsed() / double(n) : 0.0;  // duration 0: no step at all
  std::cout << "springlab-run: " << run_estimate(steps, per_step) << '\n';
  return done;
}

// CLI11 2.5 and later wrap each option's description at 65 columns and reflow the footer (the
// parameter table) into one paragraph; earlier versions print both as written, and have neither
// setting. The help reads the same with every version (issue 36: CLI11 2.6 on Debian sid).
template <class Formatter>
void help_as_written(Formatter& formatter) {
  if constexpr (requires { formatter.right_column_width(std::size_t{1000}); })
    formatter.right_column_width(1000);
  if constexpr (requires { formatter.enable_footer_formatting(false); })
    formatter.enable_footer_formatting(false);
}

Progress::Settings progress_settings() {
  Progress::Settings settings;
  settings.terminal = runner::stderr_is_terminal();
  return settings;
}

// Ctrl-C (SIGINT), SIGTERM or SIGHUP asks the run to stop after its current step and row: the
// CSV then ends in whole rows, and the run says where it stopped. A step of a large grid can take
// a minute on a busy machine, so the run says at once that it heard, and that a second signal
// ends it at once.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void ask_to_stop(int signal) {
  stop_signal = signal;
  // Only async-signal-safe calls here: a write of a fixed text.
  static const char said[] =
      "springlab-run: stopping after the current step (a large grid's step can take a while); "
      "the same signal again stops it at once\n";
  runner::write_stderr_in_handler(said, sizeof said - 1);
}

// The run stopped by a signal: its number and what was done.
struct Stopped {
  int signal;
  std::string where;
};

void run_steps(Simulation& sim, long steps, long every, std::optional<CsvOutput>& csv,
               std::optional<Progress>& progress) {
  for (long n = 1; n <= steps; ++n) {
    sim.step();
    if (csv && (n % every == 0 || n == steps)) csv->row(sim);
    if (progress) {
      char where[64];
      std::snprintf(where, sizeof where, "t = %.6g of %.6g s", sim.time(),
                    sim.parameters().duration);
      progress->after(n, where);
    }
    if (stop_signal != 0) {
      if (csv) csv->finish(sim);
      std::ostringstream where;
      where << "at t = " << sim.time() << " s, after " << n << " of " << steps << " steps"
            << (csv ? "; the CSV holds every row up to then" : "");
      throw Stopped{int(stop_signal), where.str()};
    }
  }
  sim.check();  // the energy is watched every few steps only: look once more at the end
  if (csv) csv->finish(sim);
}

int run(const Options& options) {
  const long every = every_from(options);  // a bad value is said first
  refuse_idle_options(options);
  refuse_the_scene_file(options);
  const SceneParameters p = scene_from(options);
  if (options.stability) {
    print_stability_report(std::cout, p, implementation_for(options, p));
    return done;
  }
  Simulation sim(p, implementation_for(options, p));
  const long steps = steps_for(p);
  if (options.estimate) return print_estimate(sim, steps);
  std::optional<CsvOutput> csv;
  if (options.csv) csv.emplace(*options.csv);
  std::ostream& report = csv && csv->to_stdout() ? std::cerr : std::cout;
  if (csv) csv->start(sim);

  const Diagnostics start = sim.diagnostics();
  std::optional<Progress> progress;
  if (!options.quiet) progress.emplace(steps, std::cerr, progress_settings());
  const auto clock_start = std::chrono::steady_clock::now();
  try {
    run_steps(sim, steps, every, csv, progress);
  } catch (...) {
    if (progress) progress->finish();
    throw;
  }
  if (progress) progress->finish();
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - clock_start;
  if (!options.quiet) {
    print_summary(report, sim, start, wall.count());
    print_stability(report, p);
    if (sim.implementation().student_task != 0) print_comparison(report, sim, start);
  }
  return done;
}

// What running out of memory during a run becomes when no step caught it (building a large
// scene's stability report, say): what is free and under which limit.
std::string out_of_memory() {
  const MemoryLimit limit = available_memory();
  return "ran out of memory; " + mebibytes_text(limit.bytes) + " are free now (" + limit.source +
         "): make the grid smaller, or allow the process more memory";
}

// Standard output lost (a full disk, a closed pipe): an error, not a silent exit 0.
int checked_stdout(int code) {
  const std::string failure = flush_failure(std::cout);
  if (failure.empty()) return code;
  std::cerr << "springlab-run: " << failure << '\n';
  return code == done ? lost_output : code;
}

}  // namespace

constexpr const char* exit_codes =
    "Exit codes: 0 done, 1 an unexpected error, 2 bad input, 3 the run diverged, 4 a task not "
    "written yet, 6 the output could not be written (a full disk, a closed pipe).\n"
    "Runs that last more than a few seconds show their progress on stderr; one that would last "
    "more than a few minutes says so first (--estimate says how long and stops).\n";

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"springlab-run: run a springlab scene without a window and write its state as CSV"};
  app.add_option("--scene", options.scene, "task1 ... task5, task4-damped or a scene file (TOML)")
      ->capture_default_str();
  app.add_option("--impl", options.impl, "whose code runs: the reference or the student's")
      ->capture_default_str();
  app.add_option("--integrator", options.integrator,
                 integrator_choices() + " (default: the scene's)");
  app.add_option("--dt", options.dt, "the step h in seconds, the scene's `step` (default 0.01)");
  app.add_option("--duration", options.duration, "simulated seconds, the scene's `duration`");
  app.add_option("--set", options.sets, "KEY=VALUE: change a scene parameter, e.g. structural.k=40")
      ->take_all();
  app.add_option("--every", options.every, "with --csv: write every N-th step (N >= 1; default 1)");
  app.add_option("--csv", options.csv, "FILE, or - for standard output (default: no CSV)");
  app.add_flag("--quiet", options.quiet, "no summary, no progress");
  app.add_flag("--estimate", options.estimate,
               "time the first steps, print how long the whole run would take, and stop");
  app.add_flag("--stability", options.stability,
               "print omega_max and every integrator's critical step for the scene, and stop");
  help_as_written(*app.get_formatter());
  app.footer(parameter_list() + exit_codes);
  runner::stop_on_signals(ask_to_stop);
  // Every message quotes what the user wrote: its control characters are shown, never obeyed.
  const auto say = [](const std::string& message) {
    std::cerr << "springlab-run: " << printable_lines(message) << '\n';
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& help) {
    return checked_stdout(app.exit(help));
  } catch (const CLI::ParseError& error) {
    say(std::string(error.what()) + " (springlab-run --help lists the options)");
    return bad_input;
  }
  try {
    return checked_stdout(run(options));
  } catch (const WriteFailed& error) {
    say(error.what());
    return lost_output;
  } catch (const InvalidParameter& error) {
    say(error.what());
    return bad_input;
  } catch (const DivergenceError& error) {
    say(error.what());
    return diverged;
  } catch (const NotImplemented& error) {
    say(error.what());
    return not_written;
  } catch (const std::bad_alloc&) {
    say(out_of_memory());
    return bad_input;
  } catch (const Stopped& stopped) {
    say(std::string("stopped by SIG") + runner::signal_name(stopped.signal) + " " + stopped.where);
    return 128 + stopped.signal;  // as a shell reports a program its signal ended
  } catch (const std::exception& error) {
    say(std::string("the run stopped on an unexpected error: ") + error.what());
    return failed;
  }
}
