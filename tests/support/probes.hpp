// Probing a task function that gave a wrong value: called again on inputs chosen for the purpose,
// it says what the difference is, measured, not guessed from a list of known mistakes: a
// constant factor, an input it ignores or uses in another's place, how its value grows with an
// input, which component or which particles differ, which coefficients a step function applies.
// A finding names a mistake only when the measurements describe it exactly (on every input
// tried); otherwise it states what was measured. Each returns "" when the function agrees, and
// otherwise "likely mistake: ..." for the grader's reporter.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/types.hpp"
#include "springlab/verlet_support.hpp"
#include "springlab/wind.hpp"

#include <functional>
#include <string>
#include <vector>

namespace springlab::testing {

using SpringForce = std::function<Vec2(const Vec2&, const Vec2&, double, double)>;
using DamperForce = std::function<Vec2(const Vec2&, const Vec2&, double)>;
using ForceSum =
    std::function<void(const std::vector<Spring>&, const Vectors&, const Vectors&, Vectors&)>;
using EulerStep = std::function<void(const AccelerationFunction&, double, Vectors&, Vectors&)>;
using GravitySum = std::function<void(const Eigen::VectorXd&, const Vec2&, Vectors&)>;
using PinHold = std::function<void(const std::vector<bool>&, Vectors&)>;
using WindSum =
    std::function<void(const WindField&, double, const Vectors&, const Vectors&, Vectors&)>;
using VerletStep =
    std::function<void(const AccelerationFunction&, double, Vectors&, Vectors&, VerletHistory&)>;

/// spring_force against (1.1): its component along the spring as a law in k, L and l0, and any
/// component across it.
std::string probe_spring_force(const SpringForce& f);

/// damper_force against (1.2): the linear map from v_p and v_q it applies, in multiples of b.
std::string probe_damper_force(const DamperForce& f);

/// accumulate_spring_forces against (2.3)-(2.4): what one spring gives each end, in multiples of
/// the spring's and the damper's forces as `spring` and `damper` (task 1's functions) give them;
/// whether it adds to the forces passed in; whether every spring of a list counts.
std::string probe_force_sum(const ForceSum& f, const SpringForce& spring,
                            const DamperForce& damper);

/// explicit_euler_step against (1.4)-(1.5): the coefficients it applies to h v, h a and h² a,
/// where it evaluates a, and how many times.
std::string probe_euler_step(const EulerStep& step);

/// verlet_step against (4.1)-(4.4): the coefficients of r_n, r_{n-1} and h² a it applies, the
/// first step's start (4.3), the velocity it hands back (4.4), what it keeps as history, and with
/// dampers, the velocity their force sees (4.2).
std::string probe_verlet_step(const VerletStep& step);

/// add_gravity against (5.2): per particle, its multiple of m_i g, and whether it adds.
std::string probe_gravity(const GravitySum& f);

/// add_wind against (5.3): how what it adds changes with each particle's velocity (which
/// components, linearly or not, with which coefficient against the wind's own drag c), and with
/// its place and time.
std::string probe_wind(const WindSum& f);

/// hold_pinned against (5.5): which particles' accelerations it sets to zero, and which
/// components.
std::string probe_pins(const PinHold& f);

/// The functions of an implementation as the probes take them.
inline SpringForce spring_force_of(const Implementation& impl) {
  return impl.spring_force;
}
inline DamperForce damper_force_of(const Implementation& impl) {
  return impl.damper_force;
}
inline ForceSum force_sum_of(const Implementation& impl) {
  return impl.accumulate_spring_forces;
}
inline EulerStep euler_step_of(const Implementation& impl) {
  return impl.explicit_euler_step;
}
inline GravitySum gravity_of(const Implementation& impl) {
  return impl.add_gravity;
}
inline PinHold pins_of(const Implementation& impl) {
  return impl.hold_pinned;
}
inline WindSum wind_of(const Implementation& impl) {
  return impl.add_wind;
}
inline VerletStep verlet_step_of(const Implementation& impl) {
  return impl.verlet_step;
}

}  // namespace springlab::testing
