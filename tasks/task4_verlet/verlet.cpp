// Task 4: one Störmer–Verlet step with a central-difference velocity. Handout section 4.
// Declaration, with every argument's meaning and unit: common/include/springlab/task4_verlet.hpp
#include "springlab/task4_verlet.hpp"

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                            Vectors& v, VerletHistory& history) {
  // TODO(T4): the first step (4.3), then (4.1) and (4.2) solved together, then (4.4).
  not_implemented_yet(4, __func__, __FILE__, acceleration, h, r, v, history);
}
