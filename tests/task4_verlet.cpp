// Task 4: the Störmer–Verlet step with a central-difference velocity, (4.1)-(4.5).
// Every expectation comes from physics or from the theory of the method, computed here.
#include "springlab/task4_verlet.hpp"
#include "lab_testing.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/errors.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>

using namespace springlab;
using namespace springlab::testing;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// The damped oscillator a = -w2 r - c v, the same for every coordinate of every particle.
struct LinearOscillator {
  LinearOscillator(double w2_, double c_) : w2(w2_), c(c_) {}
  double w2, c;
  long evaluations = 0;
  Vectors storage;
  AccelerationFunction function() {
    return [this](const Vectors& r, const Vectors& v) -> const Vectors& {
      ++evaluations;
      storage = -w2 * r - c * v;
      return storage;
    };
  }
};

double stretch_of(const Simulation& s) {
  const Vectors& r = s.particles().position;
  return (r.col(1) - r.col(0)).norm() - s.scene().springs.front().rest_length;
}

}  // namespace

TEST_CASE("Verlet: two steps checked by hand on a damped oscillator",
          "[task4][verlet][integrator]") {
  INFO("(4.3) r_-1 = r0 - h v0 + h^2/2 a0; (4.1)+(4.2) solved exactly; (4.4) the new velocity");
  // For a = -w2 r - c v, (4.1) with (4.2) is linear in r_{n+1}:
  //   (1 + h c/2) r_{n+1} = (2 - h² w2) r_n - (1 - h c/2) r_{n-1}.
  LinearOscillator oscillator{16.0, 0.8};
  const double h = 0.05;
  Vectors r(2, 2), v(2, 2);
  r << 1.0, -0.5, 0.25, 2.0;
  v << 0.0, 1.5, -1.0, 0.5;
  const Vectors r0 = r, v0 = v;
  const Vectors r_minus = r0 - h * v0 + 0.5 * h * h * (-oscillator.w2 * r0 - oscillator.c * v0);
  const auto next = [&](const Vectors& now, const Vectors& before) {
    const Vectors result =
        ((2.0 - h * h * oscillator.w2) * now - (1.0 - h * oscillator.c / 2.0) * before) /
        (1.0 + h * oscillator.c / 2.0);
    return result;
  };
  VerletHistory history;
  const AccelerationFunction model = oscillator.function();
  verlet_step(model, h, r, v, history);
  const Vectors r1 = next(r0, r_minus);
  CHECK((r - r1).norm() <= 1e-12);
  CHECK((v - (3.0 * r1 - 4.0 * r0 + r_minus) / (2.0 * h)).norm() <= 1e-10);
  CHECK(history.has_previous);
  CHECK((history.previous_position - r0).norm() <= 1e-15);
  verlet_step(model, h, r, v, history);
  const Vectors r2 = next(r1, r0);
  CHECK((r - r2).norm() <= 1e-12);
  CHECK((v - (3.0 * r2 - 4.0 * r1 + r0) / (2.0 * h)).norm() <= 1e-10);
}

TEST_CASE("Verlet: without dampers a step needs only two evaluations, with them a few",
          "[task4][verlet][integrator]") {
  INFO("(4.1)-(4.2): with no velocity dependence the second estimate already agrees");
  Vectors r = Vectors::Constant(2, 3, 0.5), v = Vectors::Constant(2, 3, -0.25);
  VerletHistory history;
  LinearOscillator undamped{16.0, 0.0};
  const AccelerationFunction plain = undamped.function();
  verlet_step(plain, 0.01, r, v, history);  // the first step adds one evaluation, for (4.3)
  const long first = undamped.evaluations;
  verlet_step(plain, 0.01, r, v, history);
  CHECK(undamped.evaluations - first <= 2);
  LinearOscillator damped{16.0, 1.0};
  const AccelerationFunction with_dampers = damped.function();
  verlet_step(with_dampers, 0.01, r, v, history);
  // Each estimate shrinks the error by h c / 2; from a guess good to about h^2 the estimates
  // reach the 1e-12 of velocity_settled in log(1e-12 / h^2) / log(h c / 2) passes, plus one
  // that confirms it and one to spare.
  const double passes = std::ceil(std::log(1e-12 / (0.01 * 0.01)) / std::log(0.01 * 1.0 / 2)) + 2;
  CAPTURE(damped.evaluations, passes);
  CHECK(double(damped.evaluations) <= passes);
}

TEST_CASE("Verlet: a step that cannot settle is reported, not turned into NaN",
          "[task4][verlet][stability]") {
  INFO("(4.1)-(4.2) settle only while h c / 2 < 1; beyond that verlet_step throws StepFailed");
  LinearOscillator overdamped{1.0, 1000.0};
  const AccelerationFunction model = overdamped.function();
  Vectors r = Vectors::Constant(2, 2, 1.0), v = Vectors::Constant(2, 2, 1.0);
  VerletHistory history;
  // (The first step's guess, v_0, already solves (4.1)-(4.2) exactly, so it is the second that
  // must iterate.)
  CHECK_THROWS_AS(
      (verlet_step(model, 0.01, r, v, history), verlet_step(model, 0.01, r, v, history)),
      StepFailed);
}

TEST_CASE("Verlet converges with order 2 to the exact two-mass solution",
          "[task4][verlet][order]") {
  INFO("(4.2) is central, so the error is O(h^2) also with dampers; positions and velocities");
  const SceneParameters lab;  // the lab's values
  const TwoMassExact exact{lab.structural.k, lab.structural.b, lab.mass, 0.2};
  std::vector<double> position_errors, velocity_errors;
  for (double h : {0.01, 0.005, 0.0025}) {
    Simulation sim(two_masses(lab.structural.k, lab.structural.b, lab.mass, exact.u0, h, "verlet"),
                   implementation());
    double position_error = 0.0, velocity_error = 0.0;
    run(sim, std::lround(2.0 / h), [&](const Simulation& s) {
      const Vectors& v = s.particles().velocity;
      position_error = std::max(position_error, std::abs(stretch_of(s) - exact.stretch(s.time())));
      velocity_error =
          std::max(velocity_error, std::abs(v(0, 1) - v(0, 0) - exact.stretch_rate(s.time())));
    });
    position_errors.push_back(position_error);
    velocity_errors.push_back(velocity_error);
  }
  CAPTURE(position_errors, velocity_errors);
  for (std::size_t i = 0; i + 1 < position_errors.size(); ++i) {
    CHECK_THAT(observed_order(position_errors[i], position_errors[i + 1]), WithinAbs(2.0, 0.15));
    CHECK_THAT(observed_order(velocity_errors[i], velocity_errors[i + 1]), WithinAbs(2.0, 0.15));
  }
}

TEST_CASE("Verlet: momentum is conserved over thousands of steps", "[task4][verlet][momentum]") {
  INFO("no net internal force, so sum m_i (r_{n+1} - 2 r_n + r_{n-1}) = 0 and P stays constant");
  Scene scene = build_scene(task_scene(4), implementation());
  randomise(scene.particles, 0.2, 0.8, 71);
  Simulation sim(std::move(scene), implementation());
  const Vec2 start = sim.diagnostics().momentum;
  REQUIRE(start.norm() > 0.1);
  const double worst = momentum_drift(sim, 6000);
  CAPTURE(start, worst);
  CHECK(worst <= 1e-11);
}

TEST_CASE("Verlet: a mirror-symmetric start moves mirror-symmetrically", "[task4][symmetry]") {
  INFO("the 3x3 grid mirrored left-right about x = 1 mirrors its motion");
  const int n = 3;
  Scene scene = build_scene(task_scene(4), implementation());
  Vectors& r = scene.particles.position;
  r = build_scene(lab_grid(n, n, true, 0.01, "verlet"), implementation()).particles.position;
  r.col(at(0, 1, n)) += Vec2(0.0, 0.3);  // the top middle pulled up
  r.col(at(2, 0, n)) += Vec2(-0.1, -0.1);
  r.col(at(2, 2, n)) += Vec2(0.1, -0.1);
  Simulation sim(std::move(scene), implementation());
  double worst = 0.0;
  run(sim, 3000, [&](const Simulation& s) {
    const Vectors& p = s.particles().position;
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        const Vec2 a = p.col(at(row, col, n)), b = p.col(at(row, n - 1 - col, n));
        worst = std::max({worst, std::abs(a.x() + b.x() - 2.0), std::abs(a.y() - b.y())});
      }
  });
  CAPTURE(worst);
  CHECK(worst <= 1e-10);
}

TEST_CASE("Verlet is stable at the lab step on the 3x3 grid for 60 s",
          "[task4][verlet][stability]") {
  INFO("(4.5): h = 0.01 s is far below 2/w_max for the 3x3 lab grid; the dampers calm it down");
  Simulation sim(task_scene(4), implementation());
  const double start = sim.diagnostics().total();
  double early = 0.0, late = 0.0;
  const long steps = 6000;
  REQUIRE_NOTHROW(run(sim, steps, [&](const Simulation& s) {
    const double strain = largest_strain(s.scene().springs, s.particles().position);
    if (s.steps_taken() <= steps / 10) early = std::max(early, strain);
    if (s.steps_taken() > 9 * steps / 10) late = std::max(late, strain);
  }));
  CAPTURE(start, sim.diagnostics().total(), early, late);
  CHECK_THAT(sim.time(), WithinRel(60.0, 1e-12));
  CHECK(sim.diagnostics().total() < start);
  CHECK(late < early);
}

TEST_CASE("Verlet: stable just below 2/w_max, unstable just above", "[task4][verlet][stability]") {
  INFO("(4.5): the central-difference Verlet step is stable for h < 2/w_max whatever the damping");
  const SceneParameters p = task_scene(4);
  const double limit = verlet_critical_step(linearise_at_rest(p, implementation()));
  const double factor = GENERATE(0.9, 1.1);
  Scene scene = perturbed_at_rest(p, implementation(), 1e-9, 8);
  const double start = strain_norm(scene.springs, scene.particles.position);
  scene.parameters.step = factor * limit;
  const std::vector<double> history =
      strain_history(std::move(scene), implementation(), 4000, 0.0, 1e3 * start);
  // Empty when the very first step gave no number: nothing to read at its end.
  const double last = history.empty() ? std::nan("") : history.back();
  CAPTURE(limit, factor, start, history.size(), last);
  if (factor < 1.0) {
    CHECK(history.size() == 4000);  // never grew a thousandfold
    CHECK(last < start);            // the dampers won
  } else {
    CHECK(history.size() < 200);  // beyond the limit the highest mode grows by x2.4 a step
  }
}
