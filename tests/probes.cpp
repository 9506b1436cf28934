// The probes (support/probes.hpp) tested on themselves: silent on the reference's functions, and on
// a function with one mistake, a finding that names what the mistake changed. The mistakes here
// are written for this test; the probes measure, so none of them is a case they were tuned on.
#include "probes.hpp"
#include "lab_testing.hpp"
#include "spring_lists.hpp"
#include "springlab/errors.hpp"
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

// Issue 38: a finding names a mistake only when a concrete wrong version gives the function's
// values on every probe; a fit whose coefficients are not simple values is a measurement; and
// no probe's call can change a test's verdict.

TEST_CASE("Probes name no mistake that matches one spring but not the others",
          "[diagnosis][probes]") {
  // |L - l0|: right when stretched, the opposite sign when compressed. "The opposite sign" fits
  // a compressed spring alone; the probe names what fits them all.
  const auto absolute = [](const Vec2& p, const Vec2& q, double k, double l0) {
    const Vec2 d = p - q;
    return Vec2(-k * std::abs(d.norm() - l0) * d / d.norm());
  };
  const std::string found = probe_spring_force(absolute);
  INFO(found);
  CHECK_THAT(found, Contains("likely mistake") && Contains("absolute value"));
  CHECK_THAT(found, !Contains("opposite sign"));

  // The sign flipped beyond twice the rest length only: no concrete mistake of the kit's fits
  // every spring, so what was measured is said, and no cause.
  const auto far_flipped = [](const Vec2& p, const Vec2& q, double k, double l0) {
    const Vec2 right = kit().spring_force(p, q, k, l0);
    return Vec2((p - q).norm() > 2 * l0 ? Vec2(-right) : right);
  };
  const std::string measured = probe_spring_force(far_flipped);
  INFO(measured);
  CHECK_THAT(measured, Contains(" N at L = ") && !Contains("opposite sign"));

  // The length taken after normalising: zero force only where l0 = 1.
  const auto normalised_first = [](const Vec2& p, const Vec2& q, double k, double l0) {
    const Vec2 d = (p - q).normalized();
    return Vec2(-k * (d.norm() - l0) * d);
  };
  const std::string after = probe_spring_force(normalised_first);
  INFO(after);
  CHECK_THAT(after, Contains("normalised") && !Contains("is zero"));
}

TEST_CASE("Probes say a fitted coefficient such as 0.9524 as a measurement, not a mistake",
          "[diagnosis][probes]") {
  const auto scaled = [](const Vec2& p, const Vec2& q, double k, double l0) {
    return Vec2(0.9524 * kit().spring_force(p, q, k, l0));
  };
  const std::string spring = probe_spring_force(scaled);
  INFO(spring);
  CHECK_THAT(spring, Contains(" N at L = "));  // the numbers themselves, not a fitted law
  CHECK_THAT(spring, !Contains("0.9524"));

  // A force sum whose spring part is 1.003 times (1.1)'s: the numbers, not "p gets 1.003 F".
  const auto off = [](const std::vector<Spring>& springs, const Vectors& r, const Vectors& v,
                      Vectors& f) {
    for (const Spring& s : springs) {
      const Vec2 force = 1.003 * kit().spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                         kit().damper_force(v.col(s.p), v.col(s.q), s.b);
      f.col(s.p) += force;
      f.col(s.q) -= force;
    }
  };
  const std::string sum = probe_force_sum(off, kit().spring_force, kit().damper_force);
  INFO(sum);
  CHECK_THAT(sum, Contains("changes p's force by") && !Contains("1.003 F_spring"));
}

TEST_CASE("Probes name a force sum's mistake only when it holds on both ends and every list",
          "[diagnosis][probes]") {
  // The loop starts at 1: a list of one spring gives no force at either end.
  const auto skips_first = [](const std::vector<Spring>& springs, const Vectors& r,
                              const Vectors& v, Vectors& f) {
    for (std::size_t i = 1; i < springs.size(); ++i) {
      const Spring& s = springs[i];
      const Vec2 force = kit().spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                         kit().damper_force(v.col(s.p), v.col(s.q), s.b);
      f.col(s.p) += force;
      f.col(s.q) -= force;
    }
  };
  const std::string found = probe_force_sum(skips_first, kit().spring_force, kit().damper_force);
  INFO(found);
  CHECK_THAT(found, Contains("springs[0]") && !Contains("only one end"));

  // The damper given the positions: named as such, not "no multiple ... 1.003 F_spring".
  const auto positions = [](const std::vector<Spring>& springs, const Vectors& r, const Vectors&,
                            Vectors& f) {
    for (const Spring& s : springs) {
      const Vec2 force = kit().spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                         kit().damper_force(r.col(s.p), r.col(s.q), s.b);
      f.col(s.p) += force;
      f.col(s.q) -= force;
    }
  };
  const std::string damper = probe_force_sum(positions, kit().spring_force, kit().damper_force);
  INFO(damper);
  CHECK_THAT(damper, Contains("the damper is given the positions"));
}

TEST_CASE("Probes do not build a second guess on an assumption the first one broke",
          "[diagnosis][probes]") {
  // v = h a: the velocity is overwritten; a is evaluated at r0, as (1.5) says.
  const auto overwritten = [](const AccelerationFunction& a, double h, Vectors& r, Vectors& v) {
    const Vectors acceleration = a(r, v);
    r += h * v;
    v = h * acceleration;
  };
  const std::string found = probe_euler_step(overwritten);
  INFO(found);
  CHECK_THAT(found, Contains("v1 = h a") && !Contains("after moving the positions"));
}

TEST_CASE("A probe whose function throws reports it and never throws itself",
          "[diagnosis][probes]") {
  // verlet_step with a cap of its own that the probe's damped case exceeds.
  const auto capped = [](const AccelerationFunction& a, double h, Vectors& r, Vectors& v,
                         VerletHistory& history) {
    if (a(r, v).norm() > 0.0 && v.norm() > 1.0) throw StepFailed("did not settle in 10 passes");
    kit().verlet_step(a, h, r, v, history);
  };
  std::string found;
  CHECK_NOTHROW(found = probe_verlet_step(capped));
  INFO(found);
  CHECK_THAT(found, Contains("threw StepFailed") && Contains("did not settle in 10 passes"));
}

TEST_CASE("Spring lists: a guess never contradicts the pairs printed beside it",
          "[diagnosis][probes]") {
  const SpringFamilyParameters family{true, 20.0, 0.1, 1.0};
  const Offsets structural = {{0, 1}, {1, 0}}, shear = {{1, 1}, {1, -1}};
  // The right neighbour joined by index alone: [i, cols-1] to [i+1, 0]. On a 2x1 grid this
  // repeats the spring below, but the sizes probed show distinct extra pairs, not duplicates.
  const SpringList wraps = [&](int rows, int cols) {
    std::vector<Spring> springs;
    for (int p = 0; p < rows * cols; ++p) {
      if (p + 1 < rows * cols) springs.push_back({p, p + 1, SpringFamily::structural, 20, 0.1, 1});
      if (p + cols < rows * cols)
        springs.push_back({p, p + cols, SpringFamily::structural, 20, 0.1, 1});
    }
    return springs;
  };
  const ListReport wrapped = describe_list(wraps, 2, 1, structural, "structural_springs", "(2.2)");
  INFO(wrapped.mistake);
  CHECK_THAT(wrapped.mistake, Contains("wrap around to the start of the next row"));
  CHECK_THAT(wrapped.mistake, !Contains("joined twice"));

  // Every pair joined from both ends, (p, q) and (q, p): named on every size, not only here.
  const SpringList twice = [&](int rows, int cols) {
    std::vector<Spring> springs = kit().structural_springs(rows, cols, family);
    for (const Spring& s : kit().structural_springs(rows, cols, family))
      springs.push_back({s.q, s.p, s.family, s.k, s.b, s.rest_length});
    return springs;
  };
  const ListReport doubled = describe_list(twice, 1, 2, structural, "structural_springs", "(2.2)");
  INFO(doubled.mistake);
  CHECK_THAT(doubled.mistake, Contains("likely mistake") && Contains("each pair is joined twice"));

  // An extra pair on one row whose index differs as a diagonal neighbour's does ([0, 0]-[0, 4]
  // on 5 columns), in the first row only: no concrete mistake of the kit's gives it, so no cause
  // is given, and it is not called a "wrap around a row's end".
  const SpringList same_row = [&](int rows, int cols) {
    std::vector<Spring> springs = kit().shear_springs(rows, cols, family);
    springs.push_back({0, cols - 1, SpringFamily::shear, 20, 0.1, 1});
    return springs;
  };
  const ListReport row = describe_list(same_row, 3, 5, shear, "shear_springs", "(3.1)");
  INFO(row.compared);
  INFO(row.mistake);
  CHECK_THAT(row.mistake, Contains("on one row") && !Contains("wrap"));
}
