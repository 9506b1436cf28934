// Attack on the limits: verlet_step ignores every signal it can (SIGXCPU, which the processor-time
// limit sends first, SIGTERM, SIGINT, SIGHUP, SIGALRM), blocks the rest, and then spins forever.
// The grader must still end each task 4 test (SIGKILL cannot be ignored) and say it timed out
// or used too much processor time.
#include "springlab/task4_verlet.hpp"

#include <signal.h>

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction&, double, Vectors&, Vectors&,
                            VerletHistory&) {
  for (const int s : {SIGXCPU, SIGTERM, SIGINT, SIGHUP, SIGALRM, SIGVTALRM, SIGPROF, SIGUSR1})
    signal(s, SIG_IGN);
  sigset_t all;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, nullptr);
  volatile long spins = 0;
  for (;;) spins = spins + 1;
}
