// The six integrators (integrator.hpp, handout/integrators.md): names, cost, orders against the
// exact two-mass solution, steps checked by hand, momentum, pins and energy. Every expected value
// comes from the theory of the method, computed here.
#include "lab_testing.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/this_implementation.hpp"
#include "textbook_verlet.hpp"

#include <Eigen/Cholesky>

#include <cmath>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::Contains;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

namespace {

struct Method {
  const char* name;
  int order;        // of accuracy, with dampers
  int evaluations;  // of a(r, v) per step, after the first
  double h;         // a step in the asymptotic range for the two masses (and stable)
};

const Method methods[] = {{"explicit-euler", 1, 1, 0.002},
                          {"symplectic-euler", 1, 1, 0.004},
                          {"verlet", 2, 0, 0.01},
                          {"velocity-verlet", 2, 1, 0.01},
                          {"rk4", 4, 4, 0.02},
                          {"implicit-euler", 1, 1, 0.002},
                          {"xpbd", 1, 0, 0.02}};  // no a(r, v): tests/xpbd.cpp counts its work

double stretch_rate_of(const Simulation& s) {
  const Vectors& v = s.particles().velocity;
  return v(0, 1) - v(0, 0);
}

// A 3x3 lab grid at step h, particle 8 pulled out as in task 4.
SceneParameters grid(double h, const std::string& integrator) {
  SceneParameters p = task_scene(4);
  p.step = h;
  p.integrator = integrator;
  return p;
}

// The highest frequency of the 3x3 lab grid at rest, rad/s.
double grid_frequency() {
  return highest_frequency(linearise_at_rest(grid(0.01, "rk4"), implementation()));
}

}  // namespace

TEST_CASE("Integrators: seven names, each made by name, unknown names rejected",
          "[integrators][names]") {
  const auto names = integrator_names();
  REQUIRE(names.size() == 7);
  for (const Method& m : methods) {
    CAPTURE(m.name);
    CHECK(is_integrator_name(m.name));
    CHECK(make_integrator(m.name, implementation())->name() == m.name);
  }
  try {
    make_integrator("rk5", implementation());
    FAIL("rk5 is not an integrator, but make_integrator made one");
  } catch (const InvalidParameter& error) {
    CHECK(error.field() == "integrator");
    CHECK(error.value() == "\"rk5\"");
    CHECK(error.allowed() == integrator_choices());
    for (const auto& name : names)
      CHECK_THAT(error.allowed(), Contains(name));
  }
}

TEST_CASE("Integrators: force evaluations per step as documented", "[integrators][cost]") {
  const Method m = GENERATE(from_range(std::begin(methods), std::end(methods)));
  if (m.evaluations == 0) return;  // verlet iterates (task 4 tests its count), xpbd projects
  Simulation sim(grid(0.005, m.name), implementation());
  sim.advance(1);
  const long first = sim.force_evaluations();
  sim.advance(100);
  CAPTURE(m.name, first);
  CHECK(sim.force_evaluations() - first == 100L * m.evaluations);
  CHECK(first <= 2L * m.evaluations);  // velocity Verlet's first step also needs a(r_0, v_0)
}

TEST_CASE("Integrators: convergence order against the exact two-mass solution",
          "[integrators][order]") {
  // Errors in the stretch u and its rate u' (max over 1 s) at h, h/2, h/4 shrink by 2^order.
  const Method m = GENERATE(from_range(std::begin(methods), std::end(methods)));
  const TwoMassExact exact{lab_values.structural.k, lab_values.structural.b, lab_values.mass, 0.2};
  std::vector<double> position_errors, velocity_errors;
  for (double h : {m.h, m.h / 2, m.h / 4}) {
    Simulation sim(two_masses(exact.k, exact.b, exact.mass, exact.u0, h, m.name), implementation());
    double position = 0.0, velocity = 0.0;
    run(sim, std::lround(1.0 / h), [&](const Simulation& s) {
      position = std::max(position, std::abs(stretch_of(s) - exact.stretch(s.time())));
      velocity = std::max(velocity, std::abs(stretch_rate_of(s) - exact.stretch_rate(s.time())));
    });
    position_errors.push_back(position);
    velocity_errors.push_back(velocity);
  }
  CAPTURE(m.name, m.order, position_errors, velocity_errors);
  for (std::size_t i = 0; i + 1 < position_errors.size(); ++i) {
    CHECK_THAT(observed_order(position_errors[i], position_errors[i + 1]),
               WithinAbs(m.order, 0.15));
    CHECK_THAT(observed_order(velocity_errors[i], velocity_errors[i + 1]),
               WithinAbs(m.order, 0.15));
  }
}

TEST_CASE("Velocity Verlet: its positions obey the trapezoidal-damping recurrence",
          "[integrators][velocity-verlet]") {
  // With the last half-kick's dampers implicit, u'' = -w2 u - c u' is stepped so that
  //   (1 + hc/2) u_{n+1} = (2 - h^2 w2) u_n - (1 - hc/2) u_{n-1}   (as task 4's Verlet).
  // A lagged damper (c u'_{n+1/2} in the last kick) breaks it at order h^2 c.
  const double h = 0.02, c = 2 * lab_values.structural.b / lab_values.mass;
  const double w2 = 2 * lab_values.structural.k / lab_values.mass;
  Simulation sim(two_masses(lab_values.structural.k, lab_values.structural.b, lab_values.mass, 0.2,
                            h, "velocity-verlet"),
                 implementation());
  std::vector<double> u{stretch_of(sim)};
  run(sim, 200, [&](const Simulation& s) { u.push_back(stretch_of(s)); });
  double worst = 0.0;
  for (std::size_t n = 1; n + 1 < u.size(); ++n)
    worst = std::max(worst, std::abs((1 + h * c / 2) * u[n + 1] - (2 - h * h * w2) * u[n] +
                                     (1 - h * c / 2) * u[n - 1]));
  CAPTURE(worst);
  CHECK(worst <= 1e-13);
}

TEST_CASE("Implicit Euler: one step is backward Euler, also with the spring compressed",
          "[integrators][implicit-euler]") {
  // Along the spring the motion is linear, so the linearised step is backward Euler exactly:
  //   u'_1 = (u'_0 - h w2 u_0) / (1 + h c + h^2 w2),   u_1 = u_0 + h u'_1.
  const double u0 = GENERATE(0.2, -0.5);
  const double h = GENERATE(0.01, 1.0);
  const double c = 2 * lab_values.structural.b / lab_values.mass,
               w2 = 2 * lab_values.structural.k / lab_values.mass;
  Simulation sim(two_masses(lab_values.structural.k, lab_values.structural.b, lab_values.mass, u0,
                            h, "implicit-euler"),
                 implementation());
  sim.step();
  const double rate = (0.0 - h * w2 * u0) / (1 + h * c + h * h * w2);
  CAPTURE(u0, h);
  CHECK_THAT(stretch_rate_of(sim), WithinAbs(rate, 1e-12 * std::abs(rate)));
  CHECK_THAT(stretch_of(sim), WithinAbs(u0 + h * rate, 1e-12));
}

TEST_CASE("Integrators: momentum is conserved on a randomised 3x3 grid",
          "[integrators][momentum]") {
  // Forces obey F_qp = -F_pq; the implicit solve keeps it because K and C annihilate
  // translations (up to the conjugate-gradient tolerance).
  const Method m = GENERATE(from_range(std::begin(methods), std::end(methods)));
  Scene scene = build_scene(grid(0.005, m.name), implementation());
  randomise(scene.particles, 0.2, 0.8, 71);
  Simulation sim(std::move(scene), implementation());
  const double worst = momentum_drift(sim, 2000);
  CAPTURE(m.name, worst);
  CHECK(worst <= 1e-10);
}

TEST_CASE("Integrators: pinned particles stay exactly where they are", "[integrators][pins]") {
  const Method m = GENERATE(from_range(std::begin(methods), std::end(methods)));
  Scene scene = build_scene(grid(0.005, m.name), implementation());
  scene.particles.pinned[0] = scene.particles.pinned[2] = true;  // the top corners
  const Vectors start = scene.particles.position;
  Simulation sim(std::move(scene), implementation());
  sim.advance(1000);
  const Vectors& r = sim.particles().position;
  CAPTURE(m.name);
  for (int i : {0, 2}) {
    CHECK(r(0, i) == start(0, i));
    CHECK(r(1, i) == start(1, i));
    CHECK(sim.particles().velocity.col(i).isZero(0.0));
  }
  CHECK((r.col(4) - start.col(4)).norm() > 1e-3);  // the middle has moved
}

TEST_CASE("Energy: without dampers the symplectic methods keep the error bounded over 1e5 steps",
          "[integrators][energy]") {
  // Symplectic methods conserve a nearby "modified" energy, so E oscillates around E_0 with an
  // amplitude of order (h w)^p, without drift: the worst error of the whole run is no larger
  // than that of its first tenth (a drift would show as growth).
  const std::string method = GENERATE("symplectic-euler", "verlet", "velocity-verlet");
  const int order = method == "symplectic-euler" ? 1 : 2;
  SceneParameters p = grid(0.01, method);
  p.structural.b = p.shear.b = 0.0;
  Simulation sim(p, implementation());
  const double start = sim.diagnostics().total();
  const long steps = 100000;
  double early = 0.0, worst = 0.0;
  run(sim, steps, [&](const Simulation& s) {
    const double error = std::abs(s.diagnostics().total() - start);
    worst = std::max(worst, error);
    if (s.steps_taken() <= steps / 10) early = worst;
  });
  const double bound = std::pow(p.step * grid_frequency(), order) * start;
  CAPTURE(method, start, early, worst, bound);
  CHECK(worst <= 1.25 * early);
  CHECK(worst <= bound);
}

TEST_CASE("Energy: explicit Euler's energy grows by |1 + h lambda|^2 a step",
          "[integrators][energy]") {
  // Two masses along the spring are linear: the energy of the one mode grows as rho^(2n),
  // rho^2 = 1 - 2 zeta w h + w^2 h^2, modulated within each period. A least-squares slope of
  // ln E over many periods is ln rho^2.
  const double b = GENERATE(0.0, lab_values.structural.b);
  // A start of 1e-9 m: after 1000 steps the amplitude is still far below the rest length
  // (beyond it the masses would pass through each other and the motion stop being linear).
  const TwoMassExact exact{lab_values.structural.k, b, lab_values.mass, 1e-9};
  const double h = lab_values.step, w = exact.omega(), z = exact.zeta();
  Simulation sim(two_masses(exact.k, b, exact.mass, exact.u0, h, "explicit-euler"),
                 implementation(), no_divergence_stop());
  double sn = 0, sy = 0, snn = 0, sny = 0, count = 0;
  run(sim, 1000, [&](const Simulation& s) {
    const double n = double(s.steps_taken()), y = std::log(s.diagnostics().total());
    sn += n, sy += y, snn += n * n, sny += n * y, count += 1;
  });
  const double slope = (count * sny - sn * sy) / (count * snn - sn * sn);
  const double predicted = std::log(1 - 2 * z * w * h + w * w * h * h);
  CAPTURE(b, slope, predicted);
  CHECK_THAT(slope, WithinRel(predicted, 1e-3));
}

TEST_CASE("Energy: dampers never add energy, whatever the method", "[integrators][energy]") {
  // Damped 3x3 grid, each method within its limit (explicit Euler at half of it): E never rises
  // by more than the method's own error per step, (h w_max)^(p+1) E_0, and ends below E_0.
  const Method m = GENERATE(from_range(std::begin(methods), std::end(methods)));
  const double w = grid_frequency();
  double h = 0.01;
  if (std::string(m.name) == "explicit-euler")
    h = 0.5 * critical_step(linearise_at_rest(grid(h, m.name), implementation()), m.name);
  Simulation sim(grid(h, m.name), implementation());
  const double start = sim.diagnostics().total();
  const double per_step = std::pow(h * w, m.order + 1) * start;
  double previous = start, worst_rise = 0.0, largest = start;
  run(sim, std::lround(20.0 / h / 10.0), [&](const Simulation& s) {
    const double energy = s.diagnostics().total();
    worst_rise = std::max(worst_rise, energy - previous);
    largest = std::max(largest, energy);
    previous = energy;
  });
  CAPTURE(m.name, h, start, per_step, worst_rise, largest, previous);
  CHECK(worst_rise <= per_step);
  CHECK(largest <= start + std::pow(h * w, m.order) * start);
  CHECK(previous < 0.9 * start);
}

TEST_CASE("Implicit Euler: a step solves M + hC + h^2 K even when it is badly conditioned",
          "[integrators][implicit-euler]") {
  // A 10x10 grid at its rest shape with random velocities: f_n is the dampers' force and K the
  // stiffness at rest (no spring compressed, so nothing is clamped). The step must give
  //   (M + hC + h^2 K) dv = h (f_n - h K v_n),
  // here solved densely. At the lab's values CG converges in a few iterations; with k = 1e6 N/m,
  // m = 1e-4 kg and h = 1 s (h^2 w_max^2 ~ 1e11) it does not, and the direct fallback must.
  const bool stiff = GENERATE(false, true);
  SceneParameters p = fabric_10x10(stiff ? 1.0 : 0.01, "implicit-euler");
  if (stiff) p.structural.k = p.shear.k = 1e6, p.mass = 1e-4;
  Scene scene = build_scene(p, implementation());
  randomise(scene.particles, 0.0, 0.1, 3);
  const Particles& start = scene.particles;
  const LinearModel model = linearise(scene.springs, start.position, start.mass, start.pinned);
  const Eigen::VectorXd v0 = start.velocity.reshaped();
  const Eigen::VectorXd f0 = -model.damping * v0;
  const double h = p.step;
  const Eigen::MatrixXd a =
      Eigen::MatrixXd(model.mass.asDiagonal()) + h * model.damping + h * h * model.stiffness;
  const Eigen::VectorXd dv = a.ldlt().solve(h * (f0 - h * model.stiffness * v0));
  Simulation sim(scene, implementation());
  sim.step();
  const Eigen::VectorXd v1 = sim.particles().velocity.reshaped();
  // Two solutions of a system of condition number ~1e11 agree to about that times 1e-16.
  const double tolerance = stiff ? 1e-4 : 1e-10;
  CAPTURE(stiff, (v1 - v0 - dv).norm(), dv.norm());
  CHECK((v1 - v0 - dv).norm() <= tolerance * dv.norm());
}

TEST_CASE("Task 4's damped scene: textbook Verlet diverges where the lab's Verlet runs",
          "[integrators][verlet][damped]") {
  // The scene task4-damped (handout section 4): textbook Verlet's positions are symplectic
  // Euler's, so its limit is symplectic Euler's (2(sqrt(1 + zeta^2) - zeta)/w per mode, exact by
  // bisection of the step matrix); task 4's is 2/w_max, lowered by its iteration only once
  // h c_max / 2 nears 0.76. The scene's h lies between the two.
  const SceneParameters p = load_scene("task4-damped");
  const LinearModel model = linearise_at_rest(p, implementation());
  const double textbook = critical_step(model, "symplectic-euler");
  const double lab_verlet = critical_step(model, "verlet");
  CAPTURE(textbook, p.step, lab_verlet);
  REQUIRE(textbook < p.step);
  REQUIRE(p.step < lab_verlet);
  CHECK(p.step * fastest_damping_rate(model) / 2 < verlet_iteration_factor());

  // The equivalence, step by step over 200 steps of the scene at the lab's h (stable for both:
  // beyond the limit the growing mode would amplify the two codes' different rounding).
  // Textbook Verlet starts from r_{-1} = r_0 - h v_0: from the first step on it is symplectic
  // Euler, up to rounding.
  const Implementation& tb = textbook_verlet_implementation(implementation());
  SceneParameters stable = p;
  stable.step = 0.01;
  Simulation a(stable, tb, no_divergence_stop());
  stable.integrator = "symplectic-euler";
  Simulation b(stable, implementation(), no_divergence_stop());
  a.advance(200);
  b.advance(200);
  CHECK((a.particles().position - b.particles().position).cwiseAbs().maxCoeff() <= 1e-12);

  // The runs: textbook Verlet is stopped as diverged, the lab's calms down.
  bool diverged = false;
  try {
    Simulation run(p, tb);
    run.advance(std::lround(p.duration / p.step));
  } catch (const DivergenceError&) {
    diverged = true;
  }
  CHECK(diverged);
  Simulation lab_run(p, implementation());
  const double start = lab_run.diagnostics().total();
  lab_run.advance(std::lround(p.duration / p.step));
  CHECK(lab_run.diagnostics().total() < 1e-3 * start);
}
