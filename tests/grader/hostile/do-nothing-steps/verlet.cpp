// Not an attack, a shortcut: a step that returns its input. No evaluation is within any bound
// on evaluations, and a system that never moves keeps its momentum and its symmetry.
#include "springlab/task4_verlet.hpp"

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction&, double, Vectors&, Vectors&,
                            VerletHistory&) {}
