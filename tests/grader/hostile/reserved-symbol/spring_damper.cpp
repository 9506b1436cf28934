// Task 1: the spring and the damper between two particles. Handout section 1.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();           // no direction to push along
  return -k * (length - rest_length) * d / length;  // (1.1)
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);  // (1.2)
}

// Attack: crti's _init calls __gmon_start__ when it is defined, while the dynamic loader loads the
// library and before any filter is in place.
extern "C" void __gmon_start__() {}
