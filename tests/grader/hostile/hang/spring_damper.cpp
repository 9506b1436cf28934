// Attack: an endless loop for one stiffness only (k == 7, which "Spring: no force at the rest
// length" uses); correct physics otherwise. The grader must stop that test at its time limit and
// still grade the others.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  volatile long spins = 0;
  while (k == 7.0) spins = spins + 1;  // never ends (volatile: the loop is not optimised away)
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return -k * (length - rest_length) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
