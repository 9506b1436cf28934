// Not an attack, a shortcut: a step that returns its input.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

void springlab::explicit_euler_step(const AccelerationFunction&, double, Vectors&, Vectors&) {}
