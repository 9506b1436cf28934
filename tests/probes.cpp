// The probes (support/probes.hpp) tested on themselves: silent on the reference's functions, and on
// a function with one mistake, a finding that names what the mistake changed. The mistakes here
// are written for this test; the probes measure, so none of them is a case they were tuned on.
#include "probes.hpp"
#include "lab_testing.hpp"
#include "springlab/this_implementation.hpp"

using namespace springlab;
using namespace springlab::testing;
using lab_catch::Contains;

namespace {

// The build's own functions: the reference's, as these tests run only in the reference build.
const Implementation& kit() {
  return SPRINGLAB_IMPL::implementation();
}

}  // namespace

TEST_CASE("Probes find nothing in the reference's functions", "[diagnosis][probes]") {
  CHECK(probe_spring_force(spring_force_of(kit())).empty());
  CHECK(probe_damper_force(damper_force_of(kit())).empty());
  CHECK(probe_force_sum(force_sum_of(kit()), kit().spring_force, kit().damper_force).empty());
  CHECK(probe_euler_step(euler_step_of(kit())).empty());
  CHECK(probe_verlet_step(verlet_step_of(kit())).empty());
  CHECK(probe_gravity(gravity_of(kit())).empty());
  CHECK(probe_wind(wind_of(kit())).empty());
  CHECK(probe_pins(pins_of(kit())).empty());
}

TEST_CASE("Probes name a spring force's wrong sign or missing normalisation",
          "[diagnosis][probes]") {
  const auto reversed = [](const Vec2& p, const Vec2& q, double k, double l0) {
    return Vec2(-kit().spring_force(p, q, k, l0));
  };
  const std::string sign = probe_spring_force(reversed);
  INFO(sign);
  CHECK_THAT(sign, Contains("likely mistake") && Contains("opposite sign"));

  const auto unnormalised = [](const Vec2& p, const Vec2& q, double k, double l0) {
    const Vec2 d = p - q;
    return Vec2(-k * (d.norm() - l0) * d);
  };
  const std::string length = probe_spring_force(unnormalised);
  INFO(length);
  CHECK_THAT(length, Contains("not divided by its length"));
}

TEST_CASE("Probes measure a damper's map in multiples of b", "[diagnosis][probes]") {
  const auto own_velocity_only = [](const Vec2& vp, const Vec2&, double b) {
    return Vec2(-b * vp);
  };
  const std::string found = probe_damper_force(own_velocity_only);
  INFO(found);
  CHECK_FALSE(found.empty());
  CHECK_THAT(found, Contains("v_q"));
}

TEST_CASE("Probes see a force sum that gives both ends the same force", "[diagnosis][probes]") {
  const auto no_reaction = [](const std::vector<Spring>& springs, const Vectors& r,
                              const Vectors& v, Vectors& f) {
    for (const Spring& s : springs) {
      const Vec2 force = kit().spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                         kit().damper_force(v.col(s.p), v.col(s.q), s.b);
      f.col(s.p) += force;
      f.col(s.q) += force;
    }
  };
  const std::string found = probe_force_sum(no_reaction, kit().spring_force, kit().damper_force);
  INFO(found);
  CHECK_FALSE(found.empty());
  CHECK_THAT(found, Contains("q"));
}

TEST_CASE("Probes measure an Euler step's coefficients", "[diagnosis][probes]") {
  // Semi-implicit (symplectic) Euler: the position moves with the new velocity.
  const auto semi_implicit = [](const AccelerationFunction& a, double h, Vectors& r, Vectors& v) {
    v += h * a(r, v);
    r += h * v;
  };
  const std::string found = probe_euler_step(semi_implicit);
  INFO(found);
  CHECK_FALSE(found.empty());
  CHECK_THAT(found, Contains("h"));

  int evaluations = 0;
  const auto twice = [&evaluations](const AccelerationFunction& a, double h, Vectors& r,
                                    Vectors& v) {
    const Vectors acceleration = a(r, v);
    ++evaluations;
    a(r, v);
    r += h * v;
    v += h * acceleration;
  };
  const std::string extra = probe_euler_step(twice);
  INFO(extra);
  CHECK(evaluations > 0);
  CHECK_THAT(extra, Contains("2"));
}

TEST_CASE("Probes find a Verlet step that forgets its history", "[diagnosis][probes]") {
  const auto forgetful = [](const AccelerationFunction& a, double h, Vectors& r, Vectors& v,
                            VerletHistory& history) {
    kit().verlet_step(a, h, r, v, history);
    history.has_previous = false;
  };
  const std::string found = probe_verlet_step(forgetful);
  INFO(found);
  CHECK_FALSE(found.empty());
}

TEST_CASE("Probes measure gravity without the mass, wind squared, pins on one axis",
          "[diagnosis][probes]") {
  const auto massless = [](const Eigen::VectorXd& m, const Vec2& g, Vectors& f) {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      f.col(i) += g;
  };
  const std::string gravity = probe_gravity(massless);
  INFO(gravity);
  CHECK_FALSE(gravity.empty());

  const auto squared = [](const WindField& w, double t, const Vectors& r, const Vectors& v,
                          Vectors& f) {
    for (Eigen::Index i = 0; i < r.cols(); ++i) {
      const Vec2 relative = w.velocity(t, r.col(i)) - v.col(i);
      f.col(i) += w.drag() * relative.norm() * relative;
    }
  };
  const std::string wind = probe_wind(squared);
  INFO(wind);
  CHECK_FALSE(wind.empty());

  const auto x_only = [](const std::vector<bool>& pinned, Vectors& a) {
    for (std::size_t i = 0; i < pinned.size(); ++i)
      if (pinned[i]) a(0, static_cast<Eigen::Index>(i)) = 0.0;
  };
  const std::string pins = probe_pins(x_only);
  INFO(pins);
  CHECK_FALSE(pins.empty());
  CHECK_THAT(pins, Contains("y"));
}
