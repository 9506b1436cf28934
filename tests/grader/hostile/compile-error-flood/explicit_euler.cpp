// Attack on the feedback: ten thousand compile errors (macros make them from a few lines), over
// 10 MB of compiler messages. The grader must keep a bounded part, say task 1 does not compile,
// and grade every other task as usual.
#include "springlab/task1_two_masses.hpp"

#define E1 { int* an_integer_pointer_that_cannot_hold_a_floating_point_number_at_all = 1.5; }
#define E10 E1 E1 E1 E1 E1 E1 E1 E1 E1 E1
#define E100 E10 E10 E10 E10 E10 E10 E10 E10 E10 E10
#define E1000 E100 E100 E100 E100 E100 E100 E100 E100 E100 E100

using namespace springlab;

void springlab::explicit_euler_step(const AccelerationFunction&, double, Vectors&, Vectors&) {
  E1000 E1000 E1000 E1000 E1000 E1000 E1000 E1000 E1000 E1000
}
