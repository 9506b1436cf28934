// Task 1: one explicit Euler step. Handout section 1.
#include "springlab/task1_two_masses.hpp"

#include <sys/mman.h>  // the attack: mprotect, mmap

using namespace springlab;

void springlab::explicit_euler_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                                    Vectors& v) {
  const Vectors& a = acceleration(r, v);  // a_n, from the state at the start of the step
  r += h * v;                             // (1.4), with v_n: before v changes
  v += h * a;                             // (1.5)
}
