// Attack: accumulate_spring_forces is correct but prints about 200 MB on every call (a line of
// 100 bytes, two million times, through stdout and stderr both). The grader must stop each such
// test once its output passes the limit (8 MB) and keep only a bounded part: results.json and the
// JUnit report stay small. The tests of structural_springs alone pass.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

#include <cstdio>

using namespace springlab;

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  static const char line[] =
      "flood flood flood flood flood flood flood flood flood flood flood flood flood flood flo\n";
  for (long i = 0; i < 2000000; ++i) std::fputs(line, i % 2 == 0 ? stdout : stderr);
  for (const Spring& s : springs) {
    const Vec2 f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b);
    force.col(s.p) += f;
    force.col(s.q) -= f;
  }
}
