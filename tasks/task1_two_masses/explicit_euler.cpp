// Task 1: one explicit Euler step. Handout section 1.
// Declaration, with every argument's meaning and unit:
// common/include/springlab/task1_two_masses.hpp
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

void springlab::explicit_euler_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                                    Vectors& v) {
  // TODO(T1): one step of equations (1.4) and (1.5). Both use the state at the start of the step.
  not_implemented_yet(1, __func__, __FILE__, acceleration, h, r, v);
}
