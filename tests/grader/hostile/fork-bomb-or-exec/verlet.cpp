// Attack: a correct verlet_step that first starts a shell (system(), which forks and execs
// /bin/sh to write a file) and then forks without end. The sandbox must stop the process at the
// first attempt to create a process, and the feedback must say what tests may not do. No file
// /tmp/springlab-hostile-pwned may appear.
#include "springlab/task4_verlet.hpp"

// Declared by hand: the source policy refuses POSIX headers, but not a declaration (the sandbox
// and the test process's filter are what stop the call).
extern "C" int fork() noexcept;

#include <cstdlib>

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                            Vectors& v, VerletHistory& history) {
  [[maybe_unused]] const int status = std::system("echo pwned > /tmp/springlab-hostile-pwned");
  for (int i = 0; i < 100000; ++i)
    if (fork() < 0) break;  // a fork bomb, bounded only by the kernel
  if (!history.has_previous) {
    history.previous_position = r - h * v + 0.5 * h * h * acceleration(r, v);
    history.has_previous = true;
  }
  const Vectors& r_previous = history.previous_position;
  Vectors v_now = v;
  Vectors r_next;
  for (int iteration = 1;; ++iteration) {
    r_next = 2.0 * r - r_previous + h * h * acceleration(r, v_now);
    const Vectors v_central = (r_next - r_previous) / (2.0 * h);
    const bool settled = velocity_settled(v_central, v_now, r, h);
    v_now = v_central;
    if (settled) break;
    if (iteration == verlet_max_iterations) throw StepFailed("did not settle");
  }
  v = (3.0 * r_next - 4.0 * r + r_previous) / (2.0 * h);
  history.previous_position = r;
  r = r_next;
}
