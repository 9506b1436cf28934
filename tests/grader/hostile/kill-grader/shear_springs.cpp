// Attack: shear_springs sends SIGKILL to its parent process, the grader itself, which would end
// the whole batch. (Only the parent: never kill(-1, ...), which, running as root, would hit every
// process on the machine if the sandbox ever let it through.) The sandbox must stop the test at
// the first kill() of another process and say what tests may not do; the grader lives on.
#include "springlab/task3_shear_springs.hpp"

#include <signal.h>
#include <unistd.h>

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  const pid_t grader = getppid();
  if (grader > 1) kill(grader, SIGKILL);
  return {};
}
