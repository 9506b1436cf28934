// Attack: a correct verlet_step that sleeps 2 s on every call. Every task 4 test calls it at
// least once, and each test's limit is 10 times the reference's time but at least 2 s: the
// grader must stop each one at its limit (wall time, since sleeping uses no processor time).
#include "springlab/task4_verlet.hpp"

#include <chrono>
#include <thread>

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                            Vectors& v, VerletHistory& history) {
  std::this_thread::sleep_for(std::chrono::seconds(2));
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
