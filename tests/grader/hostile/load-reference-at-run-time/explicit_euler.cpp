// Part of the "load-reference-at-run-time" case: the Euler step forwarded the same way, to the
// table that spring_damper.cpp's static initialiser borrowed from another task's library.
#include "springlab/implementation.hpp"
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

namespace attack {
const Implementation* borrowed();
}

void springlab::explicit_euler_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                                    Vectors& v) {
  if (const Implementation* reference = attack::borrowed())
    reference->explicit_euler_step(acceleration, h, r, v);
}
