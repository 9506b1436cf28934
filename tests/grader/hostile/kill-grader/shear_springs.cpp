// Attack: shear_springs sends SIGKILL to its parent process, the grader itself, which would end
// the whole batch. (Only the parent: never kill(-1, ...), which, running as root, would hit every
// process on the machine if the sandbox ever let it through.) The sandbox must stop the test at
// the first kill() of another process and say what tests may not do; the grader lives on.
#include "springlab/task3_shear_springs.hpp"

#include <signal.h>

// Declared by hand: the source policy refuses POSIX headers, but not a declaration (the sandbox
// and the test process's filter are what stop the call).
extern "C" int getppid() noexcept;
extern "C" int kill(int, int) noexcept;

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  const int grader = getppid();
  if (grader > 1) kill(grader, SIGKILL);
  return {};
}
