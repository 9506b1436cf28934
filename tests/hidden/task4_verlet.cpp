// Task 4, hidden until the due date (tests/hidden/README.md): Verlet on a pair with values the
// public tests never use, over a longer run, and its stability limit on a larger, stiffer grid
// than the lab's 3x3.
#include "springlab/task4_verlet.hpp"
#include "lab_testing.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::WithinAbs;

TEST_CASE(
    "Verlet on two masses with another k, b, m and rest length converges with order 2 over "
    "10 s",
    "[task4][hidden][verlet][order]") {
  INFO(
      "(4.1)-(4.4): the error is O(h^2) for any k, b, m and l0, in positions and in velocities; "
      "the exact solution of u'' = -(2k/m) u - (2b/m) u' is in handout section 1");
  const TwoMassExact pair{45.0, 0.3, 0.6, 0.3};  // N/m, N·s/m, kg, m
  const double rest = 1.5, duration = 10.0;      // m, s
  std::vector<double> position_errors, velocity_errors;
  for (double h : {0.004, 0.002, 0.001}) {  // all far below 2/w (equation (4.5))
    SceneParameters p = two_masses(pair.k, pair.b, pair.mass, pair.u0, h, "verlet");
    p.structural.rest_length = rest;
    p.spacing = rest;
    Simulation sim(p, implementation());
    double position_error = 0.0, velocity_error = 0.0;
    run(sim, std::lround(duration / h), [&](const Simulation& s) {
      const Vectors& r = s.particles().position;
      const Vectors& v = s.particles().velocity;
      const double stretch = (r.col(1) - r.col(0)).norm() - rest;
      position_error = std::max(position_error, std::abs(stretch - pair.stretch(s.time())));
      velocity_error =
          std::max(velocity_error, std::abs(v(0, 1) - v(0, 0) - pair.stretch_rate(s.time())));
    });
    position_errors.push_back(position_error);
    velocity_errors.push_back(velocity_error);
  }
  CAPTURE(pair.omega(), position_errors, velocity_errors);
  for (std::size_t i = 0; i + 1 < position_errors.size(); ++i) {
    CHECK_THAT(observed_order(position_errors[i], position_errors[i + 1]), WithinAbs(2.0, 0.15));
    CHECK_THAT(observed_order(velocity_errors[i], velocity_errors[i + 1]), WithinAbs(2.0, 0.15));
  }
}

TEST_CASE("Verlet on a stiffer 4x7 grid: stable just below 2/w_max, unstable just above",
          "[task4][hidden][verlet][stability]") {
  INFO(
      "(4.5): the limit h < 2/w_max holds on any grid, whatever the damping; w_max comes from "
      "this grid's own springs and masses");
  SceneParameters p = lab_grid(4, 7, true, 0.01, "verlet");
  p.mass = 0.35;
  p.structural = {true, 80.0, 0.3, 1.0};
  p.shear.k = 25.0;
  const LinearModel model = linearise_at_rest(p, implementation());
  const double limit = verlet_critical_step(model);
  const double factor = GENERATE(0.9, 1.1);
  const double h = factor * limit;
  Scene scene = perturbed_at_rest(p, implementation(), 1e-9, 9);
  const double start = strain_norm(scene.springs, scene.particles.position);
  scene.parameters.step = h;
  const std::vector<double> history =
      strain_history(std::move(scene), implementation(), 4000, 0.0, 1e3 * start);
  // Beyond the limit the fastest mode grows by rho, the step matrix's spectral radius, every
  // step: a thousandfold in ln(1000) / ln(rho) steps, twice as many if it starts at a thousandth
  // of the strain.
  const double rho = step_growth_factor(model, "verlet", h);
  // A first step that is no number at all ends the history before it starts.
  const double last = history.empty() ? std::nan("") : history.back();
  CAPTURE(limit, factor, rho, start, history.size(), last);
  if (factor < 1.0) {
    CHECK(history.size() == 4000);  // never grew a thousandfold
    CHECK(last < start);            // the dampers won
  } else {
    CHECK(double(history.size()) < 2.0 * std::log(1e3) / std::log(rho));
  }
}
