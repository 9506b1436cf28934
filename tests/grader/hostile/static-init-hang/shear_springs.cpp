// Attack: a static initialiser that never ends, so the code never finishes loading and no test
// ever begins. The grader must stop each task 3 test at its time limit.
#include "springlab/task3_shear_springs.hpp"

using namespace springlab;

namespace {
int forever() {
  volatile long spins = 0;
  for (;;) spins = spins + 1;
}
const int never = forever();
}  // namespace

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  (void)never;
  return {};
}
