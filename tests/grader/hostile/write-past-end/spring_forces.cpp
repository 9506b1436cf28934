// A classic student bug, not an attack: besides the correct forces, accumulate_spring_forces
// writes one column past the end of `force` through its raw data pointer (as a loop that runs
// one step too far would). The plain run may pass by luck; the sanitized run must catch the
// heap-buffer-overflow and the feedback must say so.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  for (const Spring& s : springs) {
    const Vec2 f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b);
    force.col(s.p) += f;
    force.col(s.q) -= f;
  }
  double* const data = force.data();
  const Eigen::Index past_the_end = force.cols();
  data[2 * past_the_end] += 0.0;  // x of column force.cols(): one past the end
  data[2 * past_the_end + 1] += 0.0;
}
