// The six integrators at the extremes (issue "The extremes"): stiff springs and light masses, no
// damping and overdamping, huge displacements, particles on top of each other, steps from 1e-6 s
// to 1 s and bad parameters. Each case has one clear outcome, predicted by the theory of
// stability.hpp: a bounded run, or a DivergenceError that says when, where and what; never NaN.
#include "lab_testing.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/eigen_solvers.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>
#include <optional>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::Contains;
using lab_catch::WithinAbs;

namespace {

// How a run ended: the divergence it reported, or the largest and last total energy.
struct Outcome {
  std::optional<DivergenceError> divergence;
  double start = 0.0, largest = 0.0, last = 0.0;
  bool finite = true;  // the state after the run or at the report
};

Outcome run_scene(Scene scene, long steps) {
  Simulation sim(std::move(scene), implementation());
  Outcome outcome;
  outcome.start = outcome.largest = sim.diagnostics().total();
  try {
    run(sim, steps, [&](const Simulation& s) {
      outcome.largest = std::max(outcome.largest, s.diagnostics().total());
    });
    sim.check();
  } catch (const DivergenceError& error) {
    outcome.divergence = error;
  }
  outcome.last = sim.diagnostics().total();
  outcome.finite = sim.particles().position.allFinite() && sim.particles().velocity.allFinite();
  return outcome;
}

Outcome run_scene(const SceneParameters& p, long steps) {
  return run_scene(build_scene(p, implementation()), steps);
}

// A divergence report names a time within the run, an existing particle and a quantity.
void check_report(const Outcome& outcome, double h, long steps, int particles) {
  REQUIRE(outcome.divergence);
  const DivergenceError& error = *outcome.divergence;
  CAPTURE(error.what());
  CHECK(error.time() >= 0.0);
  CHECK(error.time() <= double(steps) * h * (1 + 1e-12));
  CHECK(error.particle() >= 0);
  CHECK(error.particle() < particles);
  CHECK_FALSE(error.quantity().empty());
  CHECK_THAT(std::string(error.what()), Contains("diverged at t = "));
}

// The largest damping rate c of the model (eigenvalue of M^-1 C), 1/s: task 4's Verlet
// iteration settles only while h c / 2 stays below about 0.76 (handout section 4).
double fastest_damping(const LinearModel& model) {
  const Eigen::VectorXd scale = model.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd c = scale.asDiagonal() * model.damping * scale.asDiagonal();
  return solvers::symmetric_eigen(c, false).eigenvalues().maxCoeff();
}

// Theory's verdict for p at its step: stable below the critical step (and, for Verlet, while
// its iteration can settle).
bool predicted_stable(const SceneParameters& p) {
  const LinearModel model = linearise_at_rest(p, implementation());
  if (p.step >= critical_step(model, p.integrator)) return false;
  return p.integrator != "verlet" || p.step * fastest_damping(model) / 2 < 0.76;
}

// Stable: no report and the energy never above its start beyond the method's own error. Beyond
// the limit: a report, never a silent NaN.
void check_predicted_outcome(const SceneParameters& p, long steps, double energy_tolerance) {
  const bool stable = predicted_stable(p);
  const Outcome outcome = run_scene(p, steps);
  CAPTURE(p.integrator, p.step, stable, outcome.start, outcome.largest, outcome.last);
  if (stable) {
    CHECK_FALSE(outcome.divergence);
    CHECK(outcome.finite);
    CHECK(outcome.largest <= outcome.start * (1 + energy_tolerance));
  } else {
    check_report(outcome, p.step, steps, p.rows * p.cols);
  }
}

double stretch(const Simulation& s) {
  const Vectors& r = s.particles().position;
  return (r.col(1) - r.col(0)).norm() - s.scene().springs.front().rest_length;
}

}  // namespace

TEST_CASE("Extremes: stiff springs and light masses", "[extremes][stiff]") {
  // k up to 1e6 N/m, m down to 1e-4 kg on the 3x3 grid: at the lab step every explicit method
  // is far beyond its limit and reports it; implicit Euler stays bounded. At half of each
  // method's own limit every method runs.
  const std::string method = GENERATE(from_range(integrator_names()));
  const double k = GENERATE(20.0, 1e6);
  const double m = GENERATE(0.2, 1e-4);
  if (k == 20.0 && m == 0.2) return;  // the lab's values: tested elsewhere
  SceneParameters p = task_scene(4);
  p.structural.k = p.shear.k = k;
  p.mass = m;
  p.integrator = method;
  CAPTURE(k, m);
  check_predicted_outcome(p, 200, 1e-9);
  // Implicit Euler and XPBD (backward Euler on the springs) have no limit.
  const bool unlimited = method == "implicit-euler" || method == "xpbd";
  if (!unlimited) CHECK_FALSE(predicted_stable(p));
  if (unlimited) return;
  const LinearModel model = linearise_at_rest(p, implementation());
  p.step = 0.5 * critical_step(model, method);
  if (method == "verlet") p.step = std::min(p.step, 0.5 * 1.52 / fastest_damping(model));
  REQUIRE(predicted_stable(p));
  check_predicted_outcome(p, 200, 0.5);
}

TEST_CASE("Extremes: no damping at all", "[extremes][damping]") {
  // Undamped, explicit Euler is unstable at every step; the others keep the energy within
  // their own error, (h w)^order of it (RK4 and implicit Euler only lose energy).
  const std::string method = GENERATE(from_range(integrator_names()));
  SceneParameters p = task_scene(4);
  p.structural.b = p.shear.b = 0.0;
  p.integrator = method;
  const LinearModel model = linearise_at_rest(p, implementation());
  const double hw = p.step * highest_frequency(model);
  const int order = method == "symplectic-euler" ? 1 : 2;
  if (method == "explicit-euler") CHECK(critical_step(model, method) == 0.0);
  check_predicted_outcome(p, 3000, std::pow(hw, order));
}

TEST_CASE("Extremes: heavy overdamping", "[extremes][damping]") {
  // b = 100 N*s/m (zeta = 35 for two masses): a fast damping mode with c = 1000 1/s. Explicit
  // Euler, symplectic Euler and RK4 are beyond their limits (about 2/c); Verlet's iteration
  // cannot settle (h c / 2 = 5); velocity Verlet (a direct solve) and implicit Euler run, and
  // the energy only falls.
  const std::string method = GENERATE(from_range(integrator_names()));
  const bool grid = GENERATE(false, true);
  SceneParameters p = grid ? task_scene(4) : task_scene(1);
  p.structural.b = 100.0;
  p.shear.b = 50.0;
  p.integrator = method;
  CAPTURE(grid);
  check_predicted_outcome(p, 1000, 1e-12);
  CHECK(predicted_stable(p) ==
        (method == "velocity-verlet" || method == "implicit-euler" || method == "xpbd"));
}

TEST_CASE("Extremes: two masses pulled a kilometre apart", "[extremes][displacement]") {
  // 1e7 J in the spring, speeds of 14 km/s: the masses swing through each other (the spring
  // pushes them apart again once they have crossed) and the dampers calm them. Every method
  // stable at the lab step keeps the energy within its own error and loses it; explicit Euler,
  // unstable there, is stopped with a report.
  const std::string method = GENERATE(from_range(integrator_names()));
  const SceneParameters p = two_masses(lab_values.structural.k, lab_values.structural.b,
                                       lab_values.mass, 1000.0, lab_values.step, method);
  const double hw =
      lab_values.step * TwoMassExact{lab_values.structural.k, 0, lab_values.mass, 0}.omega();
  const int order = method == "symplectic-euler" ? 1 : 2;
  const Outcome outcome = run_scene(p, 2000);
  CAPTURE(method, outcome.start, outcome.largest, outcome.last);
  if (method == "explicit-euler") {
    check_report(outcome, p.step, 2000, 2);
    return;
  }
  CHECK_FALSE(outcome.divergence);
  CHECK(outcome.finite);
  CHECK(outcome.largest <= outcome.start * (1 + std::pow(hw, order)));
  CHECK(outcome.last < 0.5 * outcome.start);
}

TEST_CASE("Extremes: a grid torn 10 m out of shape", "[extremes][displacement]") {
  // Far outside the linear range: the stable methods bring it back without gaining energy, and
  // explicit Euler (unstable at the lab step) is stopped with a report.
  const std::string method = GENERATE(from_range(integrator_names()));
  SceneParameters p = task_scene(4);
  p.displacement = Vec2(10.0, -10.0);
  p.integrator = method;
  const Outcome outcome = run_scene(p, 2000);
  CAPTURE(method, outcome.start, outcome.largest, outcome.last);
  if (method == "explicit-euler") {
    check_report(outcome, p.step, 2000, 9);
    return;
  }
  CHECK_FALSE(outcome.divergence);
  CHECK(outcome.finite);
  CHECK(outcome.largest <= 1.25 * outcome.start);
  CHECK(outcome.last < 0.5 * outcome.start);
}

TEST_CASE("Extremes: two particles at the same position", "[extremes][coincident]") {
  // The spring's direction is undefined at zero length; the kit's spring force is zero there
  // (task 1, equation (1.1)), and so is its Jacobian. Two masses at rest on top of each other
  // therefore stay put, exactly; given a velocity, they separate and the spring takes over.
  const std::string method = GENERATE(from_range(integrator_names()));
  Scene scene = build_scene(two_masses(lab_values.structural.k, lab_values.structural.b,
                                       lab_values.mass, -1.0, lab_values.step, method),
                            implementation());
  REQUIRE(scene.particles.position.col(1) == scene.particles.position.col(0));
  const Vectors start = scene.particles.position;
  {
    Simulation sim(scene, implementation());
    sim.advance(100);
    CAPTURE(method);
    CHECK(sim.particles().position == start);
    CHECK(sim.particles().velocity.isZero(0.0));
  }
  scene.particles.velocity.col(1) = Vec2(0.3, 0.4);
  Simulation sim(std::move(scene), implementation());
  sim.advance(100);
  const Vectors& r = sim.particles().position;
  CAPTURE(method, r);
  CHECK(r.allFinite());
  CHECK((r.col(1) - r.col(0)).norm() > 0.01);
}

TEST_CASE("Extremes: steps from 1e-6 s to 1 s", "[extremes][step]") {
  // Two masses. Each method runs where theory says it is stable and reports a divergence where
  // it is not; at 1e-6 s every method follows the exact solution to rounding.
  const std::string method = GENERATE(from_range(integrator_names()));
  const double h = GENERATE(1e-6, 1e-4, 1e-2, 1.0);
  SceneParameters p =
      two_masses(lab_values.structural.k, lab_values.structural.b, lab_values.mass, 0.2, h, method);
  const int order = method == "rk4" ? 4 : method == "verlet" || method == "velocity-verlet" ? 2 : 1;
  const double hw = h * TwoMassExact{lab_values.structural.k, 0, lab_values.mass, 0}.omega();
  CAPTURE(method, h);
  check_predicted_outcome(p, 2000, std::pow(hw, order));
  if (h == 1e-6) {
    Simulation sim(p, implementation());
    sim.advance(2000);
    const TwoMassExact exact{lab_values.structural.k, lab_values.structural.b, lab_values.mass,
                             0.2};
    // The global error of an order-p method: about t w (h w)^p u0, here 4e-8 m for order 1.
    const double w = exact.omega(), tolerance = 2 * sim.time() * w * std::pow(hw, order) * 0.2;
    CHECK_THAT(stretch(sim), WithinAbs(exact.stretch(sim.time()), tolerance + 1e-12));
  }
}

TEST_CASE("Extremes: a 300x300 fabric for 1000 steps", "[extremes][large]") {
  // 90 000 particles and 537 002 springs in the task 5 scene's wind, with symplectic Euler (one
  // force evaluation a step; the fabric's limit for it is near 0.077 s, far above h).
  SceneParameters p = task_scene(5);
  p.rows = p.cols = 300;
  p.integrator = "symplectic-euler";
  Simulation sim(p, implementation());
  REQUIRE(sim.scene().springs.size() == std::size_t(2 * 300 * 299 + 2 * 299 * 299 + 2 * 300 * 298));
  const Vectors start = sim.particles().position;
#ifdef __SANITIZE_ADDRESS__
  // Under AddressSanitizer a step takes 17 times as long; a memory error at this size shows in
  // the first steps, and the dev build runs all 1000.
  const long steps = 60;
#else
  const long steps = 1000;
#endif
  REQUIRE_NOTHROW(sim.advance(steps));
  REQUIRE_NOTHROW(sim.check());
  const Particles& now = sim.particles();
  CHECK(now.position.allFinite());
  CHECK(now.position.leftCols(300) == start.leftCols(300));  // the pinned top row, bit for bit
  const Vec2 moved = centre_of_mass(now.mass, now.position) - centre_of_mass(now.mass, start);
  CAPTURE(moved);
  // It fell, but never faster than free fall (the pins and springs only hold it up), and the
  // wind blowing along +x moved it that way.
  const double free_fall = 0.5 * p.gravity.acceleration.y() * sim.time() * sim.time();
  CHECK(moved.y() < 0.0);
  CHECK(moved.y() > free_fall);
  CHECK(moved.x() > 0.0);
  // No spring stretches more than the top one of a column of structural springs alone would at
  // rest (it holds the weight of 299 particles; the other families only share the load), doubled
  // for a load that arrives suddenly: the fabric is soft at the lab's values, but not torn.
  const double weight_below = (p.rows - 1) * p.mass * -p.gravity.acceleration.y();
  const double bound = 1.0 + 2.0 * weight_below / p.structural.k;
  double worst = 0.0;
  for (const Spring& s : sim.scene().springs)
    worst = std::max(worst, (now.position.col(s.p) - now.position.col(s.q)).norm() / s.rest_length);
  CAPTURE(worst, bound);
  CHECK(worst < bound);
}

TEST_CASE("Extremes: bad parameters are rejected with the field, the value and the range",
          "[extremes][parameters]") {
  struct Case {
    const char* key;
    const char* value;
  };
  const Case bad =
      GENERATE(Case{"step", "0"}, Case{"step", "-1e-6"}, Case{"step", "20"}, Case{"step", "nan"},
               Case{"mass", "0"}, Case{"mass", "-1e-4"}, Case{"structural.k", "-1e6"},
               Case{"shear.b", "-0.05"}, Case{"shear.rest_length", "0"}, Case{"integrator", "rk5"},
               Case{"integrator", ""});
  SceneParameters p = task_scene(4);
  std::optional<InvalidParameter> error;
  try {
    set_parameter(p, bad.key, bad.value);
    validate(p);
  } catch (const InvalidParameter& e) {
    error = e;
  }
  CAPTURE(bad.key, bad.value);
  REQUIRE(error);
  CAPTURE(error->what());
  CHECK(error->field() == bad.key);
  if (std::string(bad.key) == "integrator") {
    CHECK(error->value() == "\"" + std::string(bad.value) + "\"");
  } else {  // the value as a number, with its unit
    const double shown = std::stod(error->value()), given = std::stod(bad.value);
    CHECK((shown == given || (std::isnan(shown) && std::isnan(given))));
  }
  CHECK_FALSE(error->allowed().empty());
}

TEST_CASE("Extremes: the stability theory rejects unknown integrators", "[extremes][parameters]") {
  const LinearModel model = linearise_at_rest(task_scene(1), implementation());
  CHECK_THROWS_AS(critical_step(model, "rk5"), InvalidParameter);
  CHECK_THROWS_AS(step_matrix(model, "rk5", 0.01), InvalidParameter);
}

TEST_CASE("Extremes: a free fall of a million large steps is no runaway", "[extremes][gravity]") {
  // Issue 13 (a tester's find): RK4 integrates a free fall exactly, but the total energy is then
  // the difference of two terms near 6e20 J, and its rounding (about 1e5 J) passed the limit of
  // 1e4 times the reference energy at t = 7.6e6 s: a divergence reported on an exact run.
  SceneParameters p = task_scene(1);
  p.structural.enabled = false;
  p.displaced = "none";
  p.gravity.enabled = true;
  p.gravity.acceleration = Vec2(0.0, -1e4);
  p.integrator = "rk4";
  p.step = 10.0;
  Simulation sim(p, implementation());
  const double y0 = sim.particles().position(1, 0);
  const long steps = 1000000;
  CHECK_NOTHROW(sim.advance(steps));
  CHECK_NOTHROW(sim.check());
  // Exact: the fall from rest is g t^2 / 2, to rounding.
  const double t = double(steps) * p.step;
  CHECK_THAT((sim.particles().position(1, 0) - y0) / (-0.5 * 1e4 * t * t), WithinAbs(1.0, 1e-9));
}
