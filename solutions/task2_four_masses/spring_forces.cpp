// Task 2: the forces of all springs and dampers. Handout section 2.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  for (const Spring& s : springs) {
    const Vec2 f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b);  // (2.3)
    force.col(s.p) += f;
    force.col(s.q) -= f;  // (2.4): F_qp = -F_pq
  }
}
