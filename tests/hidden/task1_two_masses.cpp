// Task 1, hidden until the due date (tests/hidden/README.md): the spring and the Euler step with
// values the public tests never use. Their k is always the lab's 20 N/m, so code that wrote 20 in
// place of k passes them all; physics holds for every k, b, m and rest length.
#include "springlab/task1_two_masses.hpp"
#include "lab_testing.hpp"
#include "mistakes.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>
#include <numbers>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

namespace {

// The task 1 scene with its own rest length: the masses start that far apart (plus u0).
SceneParameters two_masses_apart(const TwoMassExact& pair, double rest, double h) {
  SceneParameters p = two_masses(pair.k, pair.b, pair.mass, pair.u0, h, "explicit-euler");
  p.structural.rest_length = rest;
  p.spacing = rest;
  return p;
}

}  // namespace

TEST_CASE("Spring: Hooke's law holds for stiffnesses other than the lab's 20 N/m",
          "[task1][hidden][spring]") {
  INFO("equation (1.1): F_pq = -k (|r_p - r_q| - l0) (r_p - r_q) / |r_p - r_q|, with the k passed");
  const double k = GENERATE(3.5, 45.0, 120.0);
  const double rest = GENERATE(0.8, 2.5);
  const double ratio = GENERATE(1.4, 0.7);  // L / l0: stretched, compressed
  const double angle = 30.0 * std::numbers::pi / 180.0;
  const Vec2 towards_q(-std::cos(angle), -std::sin(angle));
  const Vec2 r_q(-0.5, 1.5);
  const Vec2 r_p = r_q - ratio * rest * towards_q;
  CAPTURE(k, rest, ratio);
  const Vec2 f = spring_force(r_p, r_q, k, rest);
  // Stretched, the spring pulls p towards q with k·(L - l0); compressed, it pushes p away.
  const double pull = k * (ratio - 1.0) * rest;
  INFO(recognise(f.dot(towards_q),
                 {{"the force uses k = 20 N/m, the lab's value, not the k passed in (1.1)",
                   20.0 * (ratio - 1.0) * rest}},
                 1e-9 * (1.0 + std::abs(pull))));
  CHECK_THAT(f.dot(towards_q), WithinRel(pull, 1e-12));
  CHECK_THAT(f.x() * towards_q.y() - f.y() * towards_q.x(), WithinAbs(0.0, 1e-12));
}

TEST_CASE(
    "Two masses with another k, b, m and rest length: explicit Euler converges with order 1 "
    "to their exact solution over 3 s",
    "[task1][hidden][euler][order]") {
  INFO(
      "handout section 1: the stretch obeys u'' = -(2k/m) u - (2b/m) u' for any k, b, m and l0; "
      "explicit Euler's global error is O(h)");
  const TwoMassExact pair{45.0, 0.3, 0.6, 0.3};  // N/m, N·s/m, kg, m
  const double rest = 1.5, duration = 3.0;       // m, s
  std::vector<double> errors;
  // Every h is below b/k, where Euler's step stops growing the oscillation (equation (1.6)).
  for (double h : {1e-3, 5e-4, 2.5e-4}) {
    Simulation sim(two_masses_apart(pair, rest, h), implementation());
    double error = 0.0;
    run(sim, std::lround(duration / h), [&](const Simulation& s) {
      const Vectors& r = s.particles().position;
      const double stretch = (r.col(1) - r.col(0)).norm() - rest;
      error = std::max(error, std::abs(stretch - pair.stretch(s.time())));
    });
    errors.push_back(error);
  }
  CAPTURE(pair.omega(), pair.zeta(), errors);
  CHECK_THAT(observed_order(errors[0], errors[1]), WithinAbs(1.0, 0.15));
  CHECK_THAT(observed_order(errors[1], errors[2]), WithinAbs(1.0, 0.15));
}
