// The position Verlet of most textbooks, for comparison with task 4's (handout section 4, "Textbook
// Verlet and this one"): (4.1) with the acceleration evaluated once, at the velocity handed back by
// the step before, which is the backward difference v_n = (r_n − r_{n−1})/h, half a step late.
// Eliminating v shows that its positions are symplectic Euler's, so its limit is that method's,
// 2(√(1 + ζ²) − ζ)/ω per mode, below task 4's 2/ω whenever a mode is damped. Used by the
// trade-off study and the tests of the damped task 4 scene; never a kit integrator.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/types.hpp"

namespace springlab {

/// One textbook Verlet step: r_{n+1} = 2 r_n − r_{n−1} + h² a(r_n, v_n), then
/// v_{n+1} = (r_{n+1} − r_n)/h. It starts from r_{−1} = r_0 − h v_0, the position whose
/// backward difference is v_0: from its first step on, its positions are symplectic Euler's.
inline void textbook_verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                                 Vectors& v, VerletHistory& history) {
  if (!history.has_previous) {  // the start the backward difference itself implies
    history.has_previous = true;
    history.previous_position = r - h * v;
  }
  Vectors next = 2.0 * r - history.previous_position + h * h * acceleration(r, v);
  v = (next - r) / h;
  history.previous_position = r;
  r = std::move(next);
}

/// `base` with its Verlet step replaced by textbook_verlet_step (the kit's fast force path off:
/// the table is not the solutions' own).
inline const Implementation& textbook_verlet_implementation(const Implementation& base) {
  static Implementation textbook = [&] {
    Implementation copy = base;
    copy.name = "textbook-verlet";
    copy.verlet_step = &textbook_verlet_step;
    copy.kit_model = nullptr;
    return copy;
  }();
  return textbook;
}

}  // namespace springlab
