// Attack: read the kit's solution through the compiler's error messages. The include check runs
// only on code that compiles; this never does, and the first 60 lines of the messages are the
// feedback. verlet_step(...) loses its parameters, so each statement of the body is an error of
// its own ("not declared"), and GCC echoes each one's source line.
#include "springlab/task4_verlet.hpp"  // first, so that #pragma once skips it below
namespace springlab {
void leak();
}
#define verlet_step(...) leak()
#include "@KIT@/solutions/task4_verlet/verlet.cpp"
