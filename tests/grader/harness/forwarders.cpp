// The task functions as the kit's tests call them (namespace `graded`): all through the table in
// use, whichever program runs the test.
#include "dispatch.hpp"
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"
#include "springlab/task3_shear_springs.hpp"
#include "springlab/task4_verlet.hpp"
#include "springlab/task5_fabric.hpp"
#include "springlab/this_implementation.hpp"

using namespace springlab;

const Implementation& springlab::implementation() {
  return *springlab_dispatch;
}

#define SPRINGLAB_DISPATCH_SKIP 0
#include "dispatch_functions.inc"
