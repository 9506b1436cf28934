# 1 "/usr/include/stdlib.h" 3
// Attack: after a UTF-8 byte-order mark, a line marker on the first line. GCC drops the mark
// and obeys the marker; a lexer that keeps the mark glued to the line sees no directive, and
// the rest of the file (the solution's, and inline assembler) passes for a system header's.
// Task 1: the spring and the damper between two particles. Handout section 1.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

#define JOIN(a, b) a##b  // no keyword in the text: the preprocessor pastes it together

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();           // no direction to push along
  return -k * (length - rest_length) * d / length;  // (1.1)
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);  // (1.2)
}
JOIN(__as, m__)(".pushsection .rodata\n.ascii \"bytes of the submission's choosing\"\n.popsection");
