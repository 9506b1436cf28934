// Not an attack: a plain syntax error (a missing semicolon). Task 1 does not compile and gets
// nothing; every other task is graded with its own (reference) files and gets full marks.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const Vec2 d = r_p - r_q
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return -k * (length - rest_length) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
