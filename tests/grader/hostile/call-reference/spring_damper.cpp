// Attack: the task functions only call the kit's reference code, declared here by hand (the
// reference is compiled into the inline namespace springlab::reference).
#include "springlab/task1_two_masses.hpp"

namespace springlab::reference {
Vec2 spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length);
Vec2 damper_force(const Vec2& v_p, const Vec2& v_q, double b);
}  // namespace springlab::reference

using namespace springlab;

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  return springlab::reference::spring_force(r_p, r_q, k, rest_length);
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return springlab::reference::damper_force(v_p, v_q, b);
}
