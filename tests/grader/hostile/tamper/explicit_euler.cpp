// Part of the "tamper" case: task 1's Euler step, correct (the case's base is the starter code,
// so both task 1 files are given; spring_damper.cpp holds the attack).
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

void springlab::explicit_euler_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                                    Vectors& v) {
  const Vectors& a = acceleration(r, v);
  r += h * v;
  v += h * a;
}
