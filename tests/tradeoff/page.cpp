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

// A message of several lines (a divergence report) as one line of a table.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '|') c = ' ';
  return text;
}

std::string setting(const Run& run) {
  return run.method == odeint_dopri5 ? "tol " + number(run.tolerance) : "h = " + number(run.h);
}

std::string cell(const Run* run, bool by_evaluations) {
  if (!run) return "none reaches it | |";
  return "`" + shown(run->method) + "` | " + setting(*run) + ", " +
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

// The scene's figures and the cheapest method for each error.
void write_cheapest(std::ostream& out, const Results& r, const Scenario& s,
                    const std::string& figures) {
  out << "\n## " << s.title << "\n\nReference: " << s.reference_note << ".\n\n";
  for (const char* figure : {"work-precision", "error-vs-step", "critical-steps", "energy"})
    out << "![" << s.name << " " << figure << "](" << figures << "/" << s.name << "-" << figure
        << ".svg)\n";
  out << "\n### The cheapest method for an error\n\n"
      << "(`xpbd` makes no force evaluations, so it is left out of the last column; its work, "
         "passes over the springs, is in its wall time.)\n\n"
      << "| largest error ≤ | fastest (wall time) | | fewest force evaluations | |\n"
      << "|---|---|---|---|---|\n";
  for (const double level : levels)
    out << "| " << number(level) << " m | " << cell(cheapest(r.runs, s.name, level, false), false)
        << " | " << cell(cheapest(r.runs, s.name, level, true), true) << " |\n";
}

// Each method's order, theory against measured.
void write_orders(std::ostream& out, const Results& r, const Scenario& s) {
  out << "\n### Measured orders\n\n| method | theory | measured | fitted over h (s) |\n"
      << "|---|---|---|---|\n";
  for (const Order& o : r.orders)
    if (o.scene == s.name)
      out << "| `" << shown(o.method) << "` | " << o.theory << " | "
          << (std::isnan(o.measured) ? "not reachable" : number(o.measured, 3)) << " | "
          << (std::isnan(o.measured) ? ""
                                     : number(o.h_from) + " … " + number(o.h_to) + " (" +
                                           std::to_string(o.points) + " steps)")
          << " |\n";
}

// Each method's critical step, theory against measured, and how they were found.
void write_critical_steps(std::ostream& out, const Results& r, const Scenario& s) {
  out << "\n### Critical steps\n\n| method | theory (s) | how | measured (s) | measured/theory |\n"
      << "|---|---|---|---|---|\n";
  for (const StepLimit& c : r.critical)
    if (c.scene == s.name)
      out << "| `" << shown(c.method) << "` | " << (c.theory > 0 ? number(c.theory, 4) : "—")
          << " | " << c.source << " | " << measured(c) << " | "
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
      if (!c->how.empty()) out << "- `" << shown(c->method) << "`: " << c->how << ".\n";
  }
}

// Every method at the lab's step, and on the fabric the implicit step's cost, timed and counted.
void write_lab_step(std::ostream& out, const Results& r, const Scenario& s) {
  out << "\n### At the lab step h = " << number(s.params.step) << " s\n\n"
      << "| method | stable | largest error (m) | error at the end (m) | energy error | "
         "evaluations a step | cost a step (evaluations' time) | wall time |\n"
         "|---|---|---|---|---|---|---|---|\n";
  std::vector<std::string> methods = study_methods(r.options);
  methods.push_back(odeint_rk4);
  for (const std::string& method : methods)
    if (const Run* run = find(r.runs, s.name, method, s.params.step))
      out << "| `" << shown(method) << "` | "
          << (run->stable ? "yes" : "**no**: " + one_line(run->unstable_why)) << " | "
          << number(run->max_error) << " | " << number(run->end_error) << " | "
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

void scene_section(std::ostream& out, const Results& r, const Scenario& s,
                   const std::string& figures) {
  write_cheapest(out, r, s, figures);
  write_orders(out, r, s);
  write_critical_steps(out, r, s);
  write_lab_step(out, r, s);
}

const Order* order_of(const Results& r, const std::string& scene, const std::string& method) {
  for (const Order& o : r.orders)
    if (o.scene == scene && o.method == method) return &o;
  return nullptr;
}

const StepLimit* limit_of(const Results& r, const std::string& scene, const std::string& method) {
  for (const StepLimit& c : r.critical)
    if (c.scene == scene && c.method == method) return &c;
  return nullptr;
}

// What the tests check of each method, in the tests' own words (tests/task1_two_masses.cpp,
// tests/task4_verlet.cpp), for the student's section.
std::string order_words(const std::string& integrator) {
  return integrator == "verlet" ? "order 2 (section 4): the errors shrink 4x when h halves"
                                : "global error O(h) (handout section 1): order 1";
}

std::string limit_words(const std::string& integrator) {
  return integrator == "verlet"
             ? "(4.5): the central-difference Verlet step is stable for h < 2/w_max whatever "
               "the damping"
             : "equation (1.6): stable only for h < 2 zeta/w (b/k for one spring)";
}

}  // namespace

// The student's explicit Euler and Verlet against theory and against the kit's same method:
// where they differ, with the law the tests check.
std::vector<std::string> student_findings(const Results& r) {
  std::vector<std::string> findings;
  for (const std::string& integrator : {std::string("explicit-euler"), std::string("verlet")}) {
    const std::string method = yours + integrator;
    for (const Scenario& s : r.scenarios) {
      const Order* o = order_of(r, s.name, method);
      const StepLimit* c = limit_of(r, s.name, method);
      const Run* mine = find(r.runs, s.name, method, s.params.step);
      const Run* kit = find(r.runs, s.name, integrator, s.params.step);
      const std::string who = "`" + shown(method) + "` on " + s.name;
      if (mine && !mine->stable &&
          mine->unstable_why.find("not implemented") != std::string::npos) {
        findings.push_back(who + ": " + one_line(mine->unstable_why));
        continue;
      }
      if (o && !std::isnan(o->measured) && std::abs(o->measured - o->theory) > 0.15)
        findings.push_back(who + ": measured order **" + number(o->measured, 3) + "**, theory " +
                           std::to_string(o->theory) + " (the tests allow ±0.15" +
                           (o->outside_range
                                ? "; fitted over its smallest steps, h = " + number(o->h_from) +
                                      " … " + number(o->h_to) +
                                      " s, whose errors stayed above a tenth of the motion"
                                : "") +
                           "). Checked: " + order_words(integrator) + ".");
      if (o && std::isnan(o->measured) && s.name == "two-masses")
        findings.push_back(who +
                           ": no order could be measured: fewer than three of its runs had an "
                           "error between rounding and a tenth of the motion.");
      if (c && c->theory > 0 && !std::isinf(c->theory) && c->measured > 0 &&
          std::abs(c->measured / c->theory - 1.0) > 0.02)
        findings.push_back(who + ": critical step measured **" + number(c->measured, 4) +
                           " s**, theory " + number(c->theory, 4) +
                           " s (the study allows ±2 %). Checked: " + limit_words(integrator) + ".");
      if (mine && kit && mine->stable && kit->stable &&
          std::abs(mine->max_error - kit->max_error) > 1e-6 * kit->max_error + 1e-12)
        findings.push_back(who + " at h = 0.01 s: largest error " + number(mine->max_error) +
                           " m, the kit's code of the same method " + number(kit->max_error) +
                           " m.");
      if (mine && kit && mine->stable != kit->stable)
        findings.push_back(who + " at h = 0.01 s: " +
                           (mine->stable ? std::string("stable")
                                         : "unstable (" + one_line(mine->unstable_why) + ")") +
                           ", the kit's code of the same method " +
                           (kit->stable ? "stable." : "unstable."));
    }
  }
  for (const DampedRun& run : r.damped.runs)
    if (is_students(run.method) && !run.stable &&
        run.why.find("not implemented") == std::string::npos)
      findings.push_back("`" + shown(run.method) + "` on task4-damped (h = " + number(r.damped.h) +
                         " s, below 2/ω_max = " + number(r.damped.verlet_limit, 4) +
                         " s): " + run.why +
                         "; the kit's Verlet runs there. Checked: " + limit_words("verlet") + ".");
  return findings;
}

namespace {

// The student's section of the page: the table, then student_findings.
void student_section(std::ostream& out, const Results& r) {
  out << "\n## Your code\n\n"
      << "Your explicit Euler (task 1, `tasks/task1_two_masses/`) and your Verlet (task 4, "
         "`tasks/task4_verlet/`) ran on the same scenes, each with the kit's code for every other "
         "task, beside the kit's methods. `explicit-euler` and `verlet` without \"(yours)\" are "
         "the kit's reference code of the same methods.\n\n"
      << "| your method | scene | measured order (theory) | critical step measured (theory) | "
         "largest error at h = 0.01 s: yours | the kit's |\n|---|---|---|---|---|---|\n";
  for (const std::string& integrator : {std::string("explicit-euler"), std::string("verlet")}) {
    const std::string method = yours + integrator;
    for (const Scenario& s : r.scenarios) {
      const Order* o = order_of(r, s.name, method);
      const StepLimit* c = limit_of(r, s.name, method);
      const Run* mine = find(r.runs, s.name, method, s.params.step);
      const Run* kit = find(r.runs, s.name, integrator, s.params.step);
      const std::string order =
          !o ? "—"
          : std::isnan(o->measured)
              ? "not measured (" + std::to_string(o->points) + " steps in range)"
              : number(o->measured, 3) + " (" + std::to_string(o->theory) + ")";
      const std::string limit = !c || c->theory <= 0 || std::isinf(c->theory)
                                    ? "—"
                                    : (c->measured > 0 ? number(c->measured, 4) : "—") + " (" +
                                          number(c->theory, 4) + ")";
      const auto error = [](const Run* run) {
        if (!run) return std::string("—");
        return run->stable ? number(run->max_error) : "unstable";
      };
      out << "| `" << shown(method) << "` | " << s.name << " | " << order << " | " << limit << " | "
          << error(mine) << " | " << error(kit) << " |\n";
    }
  }
  const std::vector<std::string> findings = student_findings(r);
  if (findings.empty()) {
    out << "\nEvery order, critical step and error above matches theory and the kit's code of "
           "the same method, and your Verlet runs the damped scene below.\n";
  } else {
    out << "\nWhere your code differs:\n\n";
    for (const std::string& f : findings)
      out << "- " << f << "\n";
    out << "\n`./lab test task1 --student` and `./lab test task4 --student` check the same laws "
           "one at a time, and name the likely mistake.\n";
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

void write_page(const Results& r, const std::string& page, const std::string& figures,
                const std::string& out_dir) {
  const fs::path page_path(page);
  if (page_path.has_parent_path()) fs::create_directories(page_path.parent_path());
  std::ofstream out(page_path);
  const std::string relative =
      fs::relative(fs::absolute(figures), fs::absolute(page_path).parent_path()).string();
  const StudyOptions& o = r.options;
  out << "# Speed against accuracy: which method, which step\n\n"
      << "<!-- Generated by `./lab tradeoff` (tests/tradeoff/page.cpp): do not edit by hand; "
         "rerun it. -->\n\n"
      << (o.student ? "Your explicit Euler and Verlet, every integrator of the kit and two of "
                      "Boost.Odeint's (`runge_kutta4` with a fixed step, `runge_kutta_dopri5` "
                      "with an adaptive one) were run on the same scenes (the kit's reference "
                      "code for everything but your two steps) on "
                    : "Every integrator of the kit and two of Boost.Odeint's (`runge_kutta4` "
                      "with a fixed step, `runge_kutta_dopri5` with an adaptive one) were run on "
                      "the same force code (the kit's reference solutions) on ")
      << r.scenarios.size() << " scenes, for " << number(o.duration)
      << " s of simulated time at steps h = 0.01 s · 2^k, k = " << o.k_min << " … " << o.k_max
      << " (the fabric from k = " << o.k_min_fabric << "), and for dopri5 at tolerances "
      << number(o.tolerances.front()) << " … " << number(o.tolerances.back())
      << " (absolute = relative). The whole study took " << seconds(r.total_seconds)
      << (o.student ? " (the short variant for your code: fewer steps, one timing)"
          : o.quick ? " (the --quick variant)"
                    : "")
      << ".\n\n"
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
      << "- **Wall time**: the minimum of " << o.repeats << " runs without any measuring, in the "
      << (o.student ? "dev" : "Release")
      << " build, one core of this machine. "
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
  if (o.student) student_section(out, r);
  for (const Scenario& s : r.scenarios)
    scene_section(out, r, s, relative);
  write_damped_section(out, r.damped, relative);
  if (r.xpbd) write_xpbd_section(out, *r.xpbd, relative, r.machine);
  advice(out, r);
  out << "\nThe numbers behind this page are in `runs.csv`, `orders.csv`, `critical.csv` and "
         "`reference.csv` of the study's output directory (`"
      << out_dir << "`). This run: " << r.machine << ".\n";
}

}  // namespace springlab::tradeoff
