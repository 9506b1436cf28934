// Not an attack: a correct task 1 that keeps a helper of its own in a header next to its files
// (spring_math.hpp). The grader copies the submission's own files with the task's, so this
// compiles and gets full marks.
#include "springlab/task1_two_masses.hpp"
#include "spring_math.hpp"

using namespace springlab;

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return hooke(k, length - rest_length) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
