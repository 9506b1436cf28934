// A classic Eigen bug, not an attack: `auto` keeps the sum as an unevaluated expression holding
// references to the two Vec2 temporaries that spring_force and damper_force returned; they are
// gone at the end of the line, so `f` reads dead stack memory when it is used. The plain run may
// pass by luck; the sanitized run must catch the use after scope and the feedback must explain it.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  for (const Spring& s : springs) {
    const auto f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b);  // (2.3)
    force.col(s.p) += f;
    force.col(s.q) -= f;  // (2.4)
  }
}
