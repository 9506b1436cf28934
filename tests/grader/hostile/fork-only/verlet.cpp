// Attack: verlet_step calls fork() (with signals not blocked, unlike system(), which blocks them
// around its clone). The sandbox must stop the test at once, and its own SIGSYS handler report
// the forbidden call: the feedback says what tests may not do.
#include "springlab/task4_verlet.hpp"

// Declared by hand: the source policy refuses POSIX headers, but not a declaration (the sandbox
// and the test process's filter are what stop the call).
extern "C" int fork() noexcept;

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction&, double, Vectors&, Vectors&,
                            VerletHistory&) {
  for (int i = 0; i < 1000; ++i)
    if (fork() <= 0) break;  // child or failure: stop
}
