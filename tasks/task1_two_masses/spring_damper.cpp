// Task 1: the spring and the damper between two particles. Handout section 1.
// Declarations, with every argument's meaning and unit:
// common/include/springlab/task1_two_masses.hpp
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  // TODO(T1): return Hooke's force on p, equation (1.1). What if r_p equals r_q?
  not_implemented_yet(1, __func__, __FILE__, r_p, r_q, k, rest_length);
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  // TODO(T1): return the damper's force on p, equation (1.2).
  not_implemented_yet(1, __func__, __FILE__, v_p, v_q, b);
}
