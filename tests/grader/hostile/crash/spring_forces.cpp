// Attack: a write through a null pointer in accumulate_spring_forces (the pointer is kept in a
// volatile variable so that the compiler cannot see it is null and must emit the store). Every
// test that adds spring forces crashes with SIGSEGV; the tests of structural_springs alone pass.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

namespace {
int* volatile nowhere = nullptr;
}

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  *nowhere = 42;  // SIGSEGV
  for (const Spring& s : springs) {
    const Vec2 f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b);
    force.col(s.p) += f;
    force.col(s.q) -= f;
  }
}
