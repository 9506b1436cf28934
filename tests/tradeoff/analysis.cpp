// From runs to the numbers theory predicts: measured orders, the cheapest method per error level,
// the cost budgets, and the --quick checks against theory.
#include "measure.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"
#include "springlab/verlet_support.hpp"

#include <cmath>
#include <limits>

namespace springlab::tradeoff {

int theoretical_order(const std::string& name) {
  // integrator.hpp; Odeint's RK4 is the same method as the kit's.
  const std::string method = integrator_of(name);
  if (method == "verlet" || method == "velocity-verlet") return 2;
  if (method == "rk4" || method == odeint_rk4) return 4;
  if (method == odeint_dopri5) return 5;
  return 1;
}

namespace {

// How far the reference moves from its start, m: the size errors are judged against.
double motion_size(const Scenario& s) {
  double size = 0.0;
  for (const Vectors& r : s.reference.position)
    size = std::max(size, position_error(r, s.reference.position.front()));
  return size;
}

}  // namespace

std::vector<Order> measured_orders(const Scenario& s, const std::vector<Run>& runs,
                                   const StudyOptions& options) {
  // The asymptotic range: errors below a tenth of the motion (where error ∝ h^p holds) and
  // above 100 times the reference's error and 1e-11 m (rounding). The fit takes the smallest
  // steps in that range, at most four, at least three.
  const double ceiling = 0.1 * motion_size(s);
  const double floor = std::max(100.0 * s.reference_error, 1e-11);
  std::vector<std::string> methods = study_methods(options);
  methods.push_back(odeint_rk4);
  std::vector<Order> orders;
  for (const std::string& method : methods) {
    Order order;
    order.scene = s.name;
    order.method = method;
    order.theory = theoretical_order(method);
    order.measured = std::nan("");
    std::vector<const Run*> fit;
    for (const Run& run : runs) {  // in increasing h
      if (run.scene != s.name || run.method != method) continue;
      const bool inside = run.stable && run.max_error >= floor && run.max_error <= ceiling;
      if (inside && fit.size() < 4) fit.push_back(&run);
      if (!inside && !fit.empty()) break;  // keep the range contiguous
    }
    // The student's code may converge to something else, or not at all: its errors then never
    // enter the range. Its order is still measured, over its four smallest stable steps, and
    // the page says so (Order::outside_range): a wrong method shows as an order far from theory.
    if (fit.size() < 3 && is_students(method)) {
      fit.clear();
      for (const Run& run : runs)
        if (run.scene == s.name && run.method == method && run.stable && run.max_error > 0 &&
            fit.size() < 4)
          fit.push_back(&run);
      order.outside_range = fit.size() >= 3;
    }
    order.points = int(fit.size());
    if (fit.size() >= 3) {
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      for (const Run* run : fit) {
        const double x = std::log(run->h), y = std::log(run->max_error);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
      }
      const double n = double(fit.size());
      order.measured = (n * sxy - sx * sy) / (n * sxx - sx * sx);
      order.h_from = fit.front()->h;
      order.h_to = fit.back()->h;
    }
    orders.push_back(order);
  }
  return orders;
}

const Run* cheapest(const std::vector<Run>& runs, const std::string& scene, double level,
                    bool by_evaluations) {
  const Run* best = nullptr;
  for (const Run& run : runs) {
    if (run.scene != scene || !run.stable || !(run.max_error <= level)) continue;
    // XPBD calls no a(r, v): counted in evaluations it would cost nothing.
    if (by_evaluations && integrator_of(run.method) == "xpbd") continue;
    const double cost = by_evaluations ? double(run.evaluations) : run.wall;
    if (!best || cost < (by_evaluations ? double(best->evaluations) : best->wall)) best = &run;
  }
  return best;
}

double evaluation_budget(const Scenario& s, const std::string& name, double h) {
  const std::string method = integrator_of(name);
  if (method == "xpbd") return 0;  // no a(r, v): it projects constraints instead
  if (method == "rk4" || method == odeint_rk4) return 4;
  if (method == "implicit-euler") return 20;
  if (method == "verlet") {
    // Task 4's step repeats (4.1)-(4.2) until two velocity estimates agree to 1e-12 of the
    // velocity scale; each repetition shrinks their difference by about h·c/2, c the largest
    // damping rate (verlet_support.hpp). One evaluation for each, one more for the first guess.
    const Scene scene = build_scene(s.params, lab_implementation());
    const double c =
        damping_rate_bound(scene.springs, scene.particles.mass, scene.particles.pinned);
    const double shrink = h * c / 2.0;
    if (shrink >= 1.0) return verlet_max_iterations;
    return std::min<double>(verlet_max_iterations,
                            2.0 + std::ceil(std::log(1e-12) / std::log(shrink)));
  }
  return 1;  // explicit-euler, symplectic-euler, velocity-verlet
}

double cost_in_evaluations(const Results& r, const Run& run) {
  for (std::size_t i = 0; i < r.scenarios.size(); ++i)
    if (r.scenarios[i].name == run.scene)
      return run.wall / double(run.steps) / r.evaluation_seconds[i];
  return std::nan("");
}

std::vector<std::string> check(const Results& r) {
  std::vector<std::string> failures;
  for (const Order& o : r.orders) {
    if (std::isnan(o.measured)) {
      if (o.scene == "two-masses")  // exact reference: every method's range is reachable
        failures.push_back(o.scene + ", " + o.method + ": no measured order (only " +
                           std::to_string(o.points) + " steps in the asymptotic range)");
      continue;
    }
    if (std::abs(o.measured - o.theory) > 0.15)
      failures.push_back(o.scene + ", " + o.method + ": measured order " + number(o.measured) +
                         ", theory " + std::to_string(o.theory) + " (allowed +-0.15)");
  }
  for (const StepLimit& c : r.critical) {
    // Only exact theory is checked, and only what was measured (the fabric's explicit Euler
    // would need millions of steps).
    if (c.theory <= 0.0 || std::isinf(c.theory) || c.source.rfind("exact", 0) != 0) continue;
    if (c.measured <= 0.0 && c.how.rfind("not measured", 0) == 0) continue;
    if (!(std::abs(c.measured / c.theory - 1.0) <= 0.02))
      failures.push_back(c.scene + ", " + c.method + ": measured critical step " +
                         number(c.measured, 5) + " s, theory " + number(c.theory, 5) +
                         " s (allowed +-2 %)");
  }
  // An implicit step's work is mostly its linear solve, which counted evaluations miss: its
  // products A x are counted too, against what conjugate-gradient theory allows (study.hpp).
  const SolverCount& solves = r.implicit_fabric_solves;
  if (solves.steps > 0) {
    if (solves.most_products > solves.products_allowed)
      failures.push_back("fabric, implicit-euler at the lab step: a step made " +
                         std::to_string(solves.most_products) +
                         " products A x; conjugate gradients need at most " +
                         std::to_string(solves.products_allowed) +
                         " (condition number <= " + number(solves.condition_bound) + ")");
    if (solves.factorisations > 0)
      failures.push_back(
          "fabric, implicit-euler at the lab step: " + std::to_string(solves.factorisations) +
          " of " + std::to_string(solves.steps) +
          " steps fell back to a sparse factorisation (conjugate gradients did "
          "not converge in 100 iterations)");
  }
  for (const Run& run : r.runs) {
    if (!run.stable || run.method == odeint_dopri5) continue;
    const Scenario* s = nullptr;
    for (const Scenario& candidate : r.scenarios)
      if (candidate.name == run.scene) s = &candidate;
    // One evaluation more in all: verlet's and velocity-verlet's first step starts them up.
    const double budget = evaluation_budget(*s, run.method, run.h);
    if (double(run.evaluations) > budget * double(run.steps) + 1.0)
      failures.push_back(run.scene + ", " + run.method + " at h = " + number(run.h) +
                         " s: " + number(double(run.evaluations) / double(run.steps)) +
                         " force evaluations a step, budget " + number(budget));
  }
  return failures;
}

}  // namespace springlab::tradeoff
