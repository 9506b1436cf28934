// handout/tradeoff.md, generated whole from the study's results: every number on it comes from
// the run that wrote it, and the advice at the end is derived from those numbers.
#include "measure.hpp"

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace springlab::tradeoff {

namespace {

namespace fs = std::filesystem;

const double levels[] = {1e-2, 1e-4, 1e-6};

std::string setting(const Run& run) {
  return run.method == odeint_dopri5 ? "tol " + number(run.tolerance) : "h = " + number(run.h);
}

std::string cell(const Run* run, bool by_evaluations) {
  if (!run) return "none reaches it | |";
  return "`" + run->method + "` | " + setting(*run) + ", " +
         (by_evaluations ? number(double(run->evaluations)) + " evaluations" : seconds(run->wall));
}

const Run* find(const std::vector<Run>& runs, const std::string& scene, const std::string& method,
                double h) {
  for (const Run& run : runs)
    if (run.scene == scene && run.method == method && std::abs(run.h / h - 1.0) < 1e-9) return &run;
  return nullptr;
}

// The measured step, with the half-width of the bracket it is the middle of.
std::string measured(const StepLimit& c) {
  if (c.measured <= 0) return "—";
  if (c.half_width <= 0) return number(c.measured, 4);
  return number(c.measured, 4) + " ± " + number(100.0 * c.half_width / c.measured, 2) + " %";
}

void scene_section(std::ostream& out, const Results& r, const Scenario& s,
                   const std::string& figures) {
  out << "\n## " << s.title << "\n\nReference: " << s.reference_note << ".\n\n";
  for (const char* figure : {"work-precision", "error-vs-step", "critical-steps", "energy"})
    out << "![" << s.name << " " << figure << "](" << figures << "/" << s.name << "-" << figure
        << ".svg)\n";
  out << "\n### The cheapest method for an error\n\n"
      << "| largest error ≤ | fastest (wall time) | | fewest force evaluations | |\n"
      << "|---|---|---|---|---|\n";
  for (const double level : levels)
    out << "| " << number(level) << " m | " << cell(cheapest(r.runs, s.name, level, false), false)
        << " | " << cell(cheapest(r.runs, s.name, level, true), true) << " |\n";
  out << "\n### Measured orders\n\n| method | theory | measured | fitted over h (s) |\n"
      << "|---|---|---|---|\n";
  for (const Order& o : r.orders)
    if (o.scene == s.name)
      out << "| `" << o.method << "` | " << o.theory << " | "
          << (std::isnan(o.measured) ? "not reachable" : number(o.measured, 3)) << " | "
          << (std::isnan(o.measured) ? ""
                                     : number(o.h_from) + " … " + number(o.h_to) + " (" +
                                           std::to_string(o.points) + " steps)")
          << " |\n";
  out << "\n### Critical steps\n\n| method | theory (s) | how | measured (s) | measured/theory |\n"
      << "|---|---|---|---|---|\n";
  for (const StepLimit& c : r.critical)
    if (c.scene == s.name)
      out << "| `" << c.method << "` | " << (c.theory > 0 ? number(c.theory, 4) : "—") << " | "
          << c.source << " | " << measured(c) << " | "
          << (c.measured > 0 && c.theory > 0 && !std::isinf(c.theory)
                  ? number(c.measured / c.theory, 4)
                  : "")
          << " |\n";
  // One sentence when every method was measured alike, else one line per method.
  std::vector<const StepLimit*> limits;
  for (const StepLimit& c : r.critical)
    if (c.scene == s.name) limits.push_back(&c);
  if (!limits.empty()) out << "\nTheory linearises the scene " << limits.front()->about << ".\n";
  bool alike = true;
  const std::string* first = nullptr;
  for (const StepLimit* c : limits)
    if (!c->how.empty())
      alike = alike && (!first || *first == c->how), first = first ? first : &c->how;
  if (first && alike) out << "\nMeasured as the " << *first << ".\n";
  if (first && !alike) {
    out << "\nMeasured:\n\n";
    for (const StepLimit* c : limits)
      if (!c->how.empty()) out << "- `" << c->method << "`: " << c->how << ".\n";
  }
  out << "\n### At the lab step h = " << number(s.params.step) << " s\n\n"
      << "| method | stable | largest error (m) | error at the end (m) | energy error | "
         "evaluations a step | cost a step (evaluations' time) | wall time |\n"
         "|---|---|---|---|---|---|---|---|\n";
  std::vector<std::string> methods = kit_methods();
  methods.push_back(odeint_rk4);
  for (const std::string& method : methods)
    if (const Run* run = find(r.runs, s.name, method, s.params.step))
      out << "| `" << method << "` | " << (run->stable ? "yes" : "**no**: " + run->unstable_why)
          << " | " << number(run->max_error) << " | " << number(run->end_error) << " | "
          << number(run->energy_error) << " | "
          << number(double(run->evaluations) / double(run->steps)) << " | "
          << (run->stable ? number(cost_in_evaluations(r, *run)) : "") << " | "
          << (run->stable ? seconds(run->wall) : "") << " |\n";
  if (s.name == "fabric" && !std::isnan(r.implicit_fabric_cost))
    out << "\nTimed on its own, batches of implicit Euler steps against as many force evaluations "
           "right after them (the median of 7 rounds), an implicit step here costs "
        << number(r.implicit_fabric_cost) << " force evaluations; its budget is "
        << number(implicit_step_budget) << ".\n";
  if (s.name == "fabric" && r.implicit_fabric_solves.steps > 0) {
    const SolverCount& c = r.implicit_fabric_solves;
    out << "\nCounted rather than timed (what `--quick` checks): over " << c.steps
        << " implicit Euler steps its conjugate gradients made at most " << c.most_products
        << " products A x in a step (" << number(c.mean_products) << " on average; each reads the "
        << "springs once, as an evaluation does) and " << c.factorisations
        << " sparse factorisations; theory allows " << c.products_allowed
        << " products a step (condition number at most " << number(c.condition_bound) << ").\n";
  }
}

// The advice, from the numbers above.
void advice(std::ostream& out, const Results& r) {
  out << "\n## What this means when you choose a method and a step\n\n";
  std::vector<std::string> unstable;
  for (const Scenario& s : r.scenarios)
    if (const Run* run = find(r.runs, s.name, "explicit-euler", s.params.step))
      if (!run->stable) unstable.push_back(s.name);
  if (!unstable.empty()) {
    out << "- **Explicit Euler is unstable at the lab step** on";
    for (std::size_t i = 0; i < unstable.size(); ++i)
      out << (i == 0 ? " " : i + 1 == unstable.size() ? " and " : ", ") << unstable[i];
    out << ": its critical step is below 0.01 s (tables above), so its energy grows every step. "
           "A short run can look fine; a long one cannot. Every other method is stable at "
           "h = 0.01 s on these scenes.\n";
  }
  for (const double level : levels) {
    std::map<std::string, int> wins;
    std::string detail;
    for (const Scenario& s : r.scenarios)
      if (const Run* run = cheapest(r.runs, s.name, level, false)) {
        ++wins[run->method];
        detail +=
            (detail.empty() ? "" : ", ") + s.name + ": `" + run->method + "` at " + setting(*run);
      }
    out << "- **For an error of " << number(level) << " m** the fastest runs were " << detail
        << ".\n";
  }
  for (const Scenario& s : r.scenarios) {
    const Run* kit = find(r.runs, s.name, "rk4", s.params.step);
    const Run* peer = find(r.runs, s.name, odeint_rk4, s.params.step);
    if (kit && peer && kit->stable && peer->stable)
      out << "- On " << s.name << " the kit's `rk4` and Odeint's `runge_kutta4` make the same "
          << "error at h = 0.01 s (" << number(kit->max_error) << " and " << number(peer->max_error)
          << " m); the kit's took " << number(kit->wall / peer->wall, 2)
          << " times Odeint's wall time.\n";
  }
  // Which orders won the tight levels.
  bool high_order_wins = true;
  for (const Scenario& s : r.scenarios)
    for (const double level : {1e-4, 1e-6})
      if (const Run* run = cheapest(r.runs, s.name, level, false))
        high_order_wins = high_order_wins && theoretical_order(run->method) >= 2;
  out << "- Halving h divides a method's error by about 2^p, p its order (measured above): a "
         "first-order method (explicit, symplectic or implicit Euler) needs a step ten times "
         "smaller for each extra digit, RK4 one only 10^(1/4) = 1.8 times smaller. "
      << (high_order_wins ? "So for errors of 1e-4 m and below the fastest run on every scene "
                            "was a method of order 2 or more, although they cost more force "
                            "evaluations a step.\n"
                          : "Even so, a first-order method was the fastest for some error of "
                            "1e-4 m or below (see the tables).\n");
  out << "- Choose h for the accuracy you need first, then check that it is below your scene's "
         "critical step (`./lab run --scene FILE --stability`): close to the critical step a "
         "method is stable but its error is of the size of the motion.\n";
  for (const Scenario& s : r.scenarios) {
    const Run* largest = nullptr;
    for (const Run& run : r.runs)
      if (run.scene == s.name && run.method == "implicit-euler" && run.stable) largest = &run;
    if (largest)
      out << "- Implicit Euler never became unstable on " << s.name
          << ", up to h = " << number(largest->h) << " s, where its largest error was "
          << number(largest->max_error)
          << " m: bounded is not the same as accurate (the energy figures show what it does to "
             "the energy). It suits stiff scenes where only stability matters.\n";
  }
}

}  // namespace

void write_page(const Results& r, const std::string& page, const std::string& figures) {
  const fs::path page_path(page);
  if (page_path.has_parent_path()) fs::create_directories(page_path.parent_path());
  std::ofstream out(page_path);
  const std::string relative =
      fs::relative(fs::absolute(figures), fs::absolute(page_path).parent_path()).string();
  const StudyOptions& o = r.options;
  out << "# Speed against accuracy: which method, which step\n\n"
      << "<!-- Generated by `./lab tradeoff` (tests/tradeoff/page.cpp): do not edit by hand; "
         "rerun it. -->\n\n"
      << "Every integrator of the kit and two of Boost.Odeint's (`runge_kutta4` with a fixed "
         "step, `runge_kutta_dopri5` with an adaptive one) were run on the same force code "
         "(the kit's reference solutions) on three scenes, for "
      << number(o.duration) << " s of simulated time at steps h = 0.01 s · 2^k, k = " << o.k_min
      << " … " << o.k_max << " (the fabric from k = " << o.k_min_fabric
      << "), and for dopri5 at tolerances " << number(o.tolerances.front()) << " … "
      << number(o.tolerances.back()) << " (absolute = relative). The whole study took "
      << seconds(r.total_seconds) << (o.quick ? " (the --quick variant)" : "") << ".\n\n"
      << "How each number is measured:\n\n"
      << "- **Error**: the largest distance |r_i − r_i,ref| over the particles, compared every "
      << number(o.sample) << " s (or every step, for steps longer than that), m. The table and "
      << "figures use its largest value over the run; the CSV also has the value at the end.\n"
      << "- **Energy error**: the largest |E − E_ref| over the same times, divided by the "
         "largest |E_ref| of the run. E is kinetic + spring + gravity energy, gravity's zero at "
         "the start positions. Divided by the largest, not the current, energy because a "
         "damped scene's energy goes to zero (or, for the fabric, passes through it).\n"
      << "- **Force evaluations**: the calls of a(r, v) the run made (Simulation counts them).\n"
      << "- **Cost a step**: the wall time of a step divided by that of one force evaluation on "
         "the same scene: what a step really costs, the integrator's own work (implicit Euler's "
         "linear solve, velocity Verlet's) included. On two particles a step's fixed costs weigh "
         "more than a 12 ns evaluation.\n"
      << "- **Wall time**: the minimum of " << o.repeats
      << " runs without any measuring, in the Release build, one core of this 2-core machine. "
         "Wall times below a millisecond are noisy.\n"
      << "- **Stable**: the run finished without the divergence watch firing, its error stayed "
         "below 10 m, and it never gained more energy over the reference than the scene ever "
         "holds (dampers only remove energy). An unstable run reaches no error level.\n"
      << "- **Order**: the least-squares slope of log(error) against log(h) over the smallest "
         "steps (at most four, at least three) whose error lies between 100 times the "
         "reference's error (and 1e-11 m) and a tenth of the motion's size: where error ∝ h^p "
         "holds.\n"
      << "- **Critical steps**: theory from `stability.hpp`, the scene linearised about its "
         "equilibrium: two masses and the grid at rest, the fabric where it hangs (gravity "
         "stretches it), found by Newton's method on the force balance. Measured on runs from "
         "that equilibrium with every particle moved randomly by 1e-6 m, judged by the growth "
         "of the springs' length changes: on two masses and the grid by bisection on h, runs "
         "long enough for growth 0.5 % beyond the limit to show; on the fabric (400 particles) "
         "by testing (1 ± 2 %)·h_c, stable below and unstable above placing the limit within "
         "2 % of theory"
      << (o.quick ? "" : ", then bisecting that bracket")
      << ". The details are under each table.\n";
  for (const Scenario& s : r.scenarios)
    scene_section(out, r, s, relative);
  advice(out, r);
  out << "\nThe numbers behind this page are in `runs.csv`, `orders.csv`, `critical.csv` and "
         "`reference.csv` of the study's output directory (`build/release/tradeoff`).\n";
}

}  // namespace springlab::tradeoff
