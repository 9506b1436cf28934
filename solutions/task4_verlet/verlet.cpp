// Task 4: one Störmer–Verlet step with a central-difference velocity. Handout section 4.
#include "springlab/task4_verlet.hpp"

using namespace springlab;

void springlab::verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                            Vectors& v, VerletHistory& history) {
  if (!history.has_previous) {  // (4.3): r_{-1} from a second-order Taylor step backwards
    history.previous_position = r - h * v + 0.5 * h * h * acceleration(r, v);
    history.has_previous = true;
  }
  const Vectors& r_previous = history.previous_position;
  Vectors v_now = v;  // the guess for v_n; (4.4) made it second-order accurate
  Vectors r_next;
  for (int iteration = 1;; ++iteration) {
    r_next = 2.0 * r - r_previous + h * h * acceleration(r, v_now);  // (4.1)
    const Vectors v_central = (r_next - r_previous) / (2.0 * h);     // (4.2)
    const bool settled = velocity_settled(v_central, v_now, r, h);
    v_now = v_central;
    if (settled) break;
    if (iteration == verlet_max_iterations)
      throw StepFailed(
          "(4.1)-(4.2) did not settle in " + std::to_string(verlet_max_iterations) +
          " iterations: the dampers are too strong for this h (h*c/2 near or above 1)");
  }
  v = (3.0 * r_next - 4.0 * r + r_previous) / (2.0 * h);  // (4.4)
  history.previous_position = r;
  r = r_next;
}
