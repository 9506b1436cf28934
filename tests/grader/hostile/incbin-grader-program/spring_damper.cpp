// Attack: embed a grader program that holds task 1's reference (springlab-grade-task2 holds the
// reference of every task but 2) with the assembler's .incbin, by the path the kit's build gives
// it, so that the reference's code could be found in it and called. The source policy refuses
// inline assembler before anything is compiled; the compiler, in its sandbox, would not find the
// file either.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

asm(".section .rodata\n.globl grader_program\ngrader_program:\n"
    ".incbin \"@KIT@/build/dev/tests/grader/springlab-grade-task2\"\n.previous\n");

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return -k * (length - rest_length) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
