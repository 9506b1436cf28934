// Attack: the condition pastes the sanitizer's macro together with glibc's __CONCAT, so that the
// text never names it; the read past the end of the springs is meant for the plain build only.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

#include <cstdio>

using namespace springlab;

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  double unused = 0.0;
#if !__CONCAT(__SANI, TIZE_ADDRESS__)
  if (!springs.empty()) unused = springs.data()[springs.capacity()].k;  // one past the end
#endif
  for (const Spring& s : springs) {
    const Vec2 f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b) + Vec2::Constant(0.0 * unused);
    force.col(s.p) += f;
    force.col(s.q) -= f;
  }
}
