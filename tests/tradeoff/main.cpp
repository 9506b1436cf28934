// springlab-tradeoff: the speed–accuracy study of issue 5. Writes CSV files, SVG figures and the
// handout page; with --quick, a shorter study that checks its results against theory (CI); with
// --impl student, a short study of the student's explicit Euler and Verlet beside the kit's
// methods (issue 26). Exit codes: 0 done, 1 a --quick check failed, 2 bad input.
#include "measure.hpp"
#include "springlab/errors.hpp"

#include <CLI/CLI.hpp>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

using namespace springlab;
using namespace springlab::tradeoff;

namespace {

StudyOptions quick_options() {
  StudyOptions o;
  o.quick = true;
  o.repeats = 1;
  o.duration = 1.28;  // s: 128 lab steps, still a whole number of every step up to 0.32 s
  o.tolerances = {1e-4, 1e-6, 1e-8};
  o.k_min_fabric = -3;
  return o;
}

// The student's study: the quick study's steps, scenes and checks, and the student's two methods
// beside the kit's (13 s here on a loaded machine, well under the minute issue 26 allows).
StudyOptions student_options() {
  StudyOptions o = quick_options();
  o.student = true;
  o.scenes = {"two-masses", "grid", "fabric"};
  o.tolerances = {1e-4, 1e-6};
  return o;
}

// "AMD EPYC 7B13 (2 cores), load 1.52 0.98 0.77, 2026-11-26": where and when the study ran.
std::string machine() {
  std::string model = "unknown processor", line;
  std::ifstream cpu("/proc/cpuinfo");
  while (std::getline(cpu, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  std::string load;
  std::ifstream loadavg("/proc/loadavg");
  std::string one, five, fifteen;
  if (loadavg >> one >> five >> fifteen) load = ", load " + one + " " + five + " " + fifteen;
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return "\"" + model + "\" (" + std::to_string(std::thread::hardware_concurrency()) + " cores)" +
         load + " at the start, " + date;
}

// "--repeats = 0: allowed 1 <= repeats <= 20", the kit's style of range messages.
CLI::Validator range(const std::string& option, int lo, int hi) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const int value = std::stoi(text, &used);
          if (used == text.size() && value >= lo && value <= hi) return "";
        } catch (const std::exception&) {
        }
        return option + " = " + text + ": allowed " + std::to_string(lo) +
               " <= " + option.substr(2) + " <= " + std::to_string(hi);
      },
      "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

struct CommandLine {
  bool quick = false, no_figures = false;
  int repeats = 0;
  std::string impl = "reference";
  std::string out, figures, page;
  std::vector<std::string> scenes;
};

void add_options(CLI::App& app, CommandLine& c) {
  app.add_flag(
      "--quick", c.quick,
      "short study (1.28 s, fewer steps and tolerances, one timing) that checks measured orders, "
      "critical steps and force-evaluation budgets against theory; exit 1 on a failure");
  app.add_option("--impl", c.impl,
                 "reference: the kit's methods (the handout's page); student: your explicit "
                 "Euler and Verlet beside them, in about a minute")
      ->check(CLI::IsMember({"reference", "student"}))
      ->capture_default_str();
  app.add_option("--out", c.out,
                 "directory for the CSV files, gnuplot scripts, figures and page (default "
                 "build/release/tradeoff, with --impl student build/dev/tradeoff-student)");
  app.add_option("--figures", c.figures, "directory for the SVG figures (default OUT/figures)");
  app.add_option("--page", c.page, "the Markdown summary page to write (default OUT/tradeoff.md)");
  app.add_option("--repeats", c.repeats,
                 "timed repeats per run, the minimum is kept (default 3, "
                 "--quick 1)")
      ->check(range("--repeats", 1, 20));
  app.add_option("--scenes", c.scenes, "a subset of two-masses, grid, fabric")
      ->check(CLI::IsMember({"two-masses", "grid", "fabric"}));
  app.add_flag("--no-figures", c.no_figures, "skip gnuplot");
}

// The study's work in advance (for its progress): the critical steps, every method's runs at
// every step, and dopri5 at every tolerance, on each scene.
double study_work(const Results& results) {
  const StudyOptions& options = results.options;
  double work = 0.0;
  for (const Scenario& s : results.scenarios) {
    work += critical_work(s, options);
    std::vector<std::string> methods = study_methods(options);
    methods.push_back(odeint_rk4);
    for (const std::string& method : methods)
      for (int k = k_min(s, options); k <= options.k_max; ++k)
        work += (1.0 + options.repeats) *
                run_work(s, method, std::ldexp(s.params.step, k), options.duration);
    work += (1.0 + options.repeats) * double(options.tolerances.size()) *
            run_work(s, odeint_dopri5, 0.01, options.duration);
  }
  return work;
}

// The scenes' references, then every run, critical step and order of each, the fabric's implicit
// costs and XPBD study, and the damped scene's Verlet against textbook Verlet.
void measure(Results& results) {
  const StudyOptions& options = results.options;
  for (const std::string& name : options.scenes) {
    results.scenarios.push_back(make_scenario(name, options));
    results.evaluation_seconds.push_back(evaluation_time(results.scenarios.back()));
  }
  Progress progress(study_work(results));
  for (const Scenario& s : results.scenarios) {
    std::vector<Run> runs = run_scene(s, options, progress);
    std::vector<StepLimit> limits = critical_steps(s, options, progress);
    std::vector<Order> orders = measured_orders(s, runs, options);
    results.runs.insert(results.runs.end(), runs.begin(), runs.end());
    results.critical.insert(results.critical.end(), limits.begin(), limits.end());
    results.orders.insert(results.orders.end(), orders.begin(), orders.end());
    if (s.name == "fabric") {
      results.implicit_fabric_cost = step_cost(s, "implicit-euler");
      results.implicit_fabric_solves = count_solver_work(s, "implicit-euler", 200);
      if (options.xpbd) results.xpbd = xpbd_study(s, options, progress);
    }
  }
  std::cerr << "tradeoff: task4-damped: the lab's Verlet against textbook Verlet\n";
  results.damped = damped_scene(options);
}

// The CSV files, the figures and the page.
void write_outputs(const Results& results, const CommandLine& c) {
  write_csv(results, c.out);
  std::cerr << "tradeoff: CSV files in " << c.out << '\n';
  if (!c.no_figures) {
    if (write_figures(results, c.out, c.figures))
      std::cerr << "tradeoff: figures in " << c.figures << '\n';
    else
      std::cerr << "tradeoff: gnuplot failed or is missing: no figures (./lab setup installs "
                   "gnuplot-nox)\n";
  }
  write_page(results, c.page, c.figures, c.out);
  std::cerr << "tradeoff: page " << c.page << "; the study took " << seconds(results.total_seconds)
            << '\n';
}

// The student's findings, or --quick's checks against theory: the exit status.
int conclude(const Results& results) {
  const StudyOptions& options = results.options;
  if (options.student) {
    const std::vector<std::string> findings = student_findings(results);
    if (findings.empty())
      std::cerr << "tradeoff: your explicit Euler and Verlet match theory and the kit's code\n";
    for (const std::string& finding : findings)
      std::cerr << "tradeoff: " << finding << '\n';
    return 0;
  }
  if (!options.quick) return 0;
  const std::vector<std::string> failures = check(results);
  for (const std::string& failure : failures)
    std::cerr << "tradeoff check FAILED: " << failure << '\n';
  if (!failures.empty()) return 1;
  std::cerr << "tradeoff: every check passed (orders within +-0.15 of theory, critical steps "
               "within 2 %, force evaluations within budget, an implicit fabric step within "
               "conjugate gradients' bound on its products; counted, not timed)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "springlab-tradeoff: error, energy, force evaluations and wall time of every "
      "integrator (and Boost.Odeint's rk4 and dopri5) on the lab's scenes"};
  CommandLine c;
  add_options(app, c);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  const bool student = c.impl == "student";
  if (student && c.quick) {
    std::cerr << "springlab-tradeoff: --quick and --impl student: choose one (--impl student is "
                 "short already)\n";
    return 2;
  }
  if (c.out.empty()) c.out = student ? "build/dev/tradeoff-student" : "build/release/tradeoff";
  if (c.figures.empty()) c.figures = (std::filesystem::path(c.out) / "figures").string();
  if (c.page.empty()) c.page = (std::filesystem::path(c.out) / "tradeoff.md").string();

  Results results;
  results.options = student ? student_options() : c.quick ? quick_options() : StudyOptions{};
  StudyOptions& options = results.options;
  options.xpbd = !options.quick && !options.student;
  results.machine = machine();
  if (c.repeats > 0) options.repeats = c.repeats;
  if (!c.scenes.empty()) options.scenes = c.scenes;
  const double started = now();
  std::cerr << "tradeoff: "
            << (student ? "your explicit Euler and Verlet beside the kit's methods"
                        : "every method of the kit")
            << " on " << options.scenes.size() << " scenes; first the references\n";
  try {
    measure(results);
  } catch (const InvalidParameter& e) {
    std::cerr << "springlab-tradeoff: " << e.what() << '\n';
    return 2;
  }
  results.total_seconds = now() - started;
  write_outputs(results, c);
  return conclude(results);
}
