// Attack: machine code lifted from a compiled reference, as bytes in an array that the section
// attribute puts into .text, where it is executable; the task function jumps into it. (The bytes
// here are "xor eax, eax; ret": the point is where they are placed, not what they do.)
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

__attribute__((section(".text"))) const unsigned char lifted[] = {0x31, 0xc0, 0xc3};

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const auto run = reinterpret_cast<int (*)()>(reinterpret_cast<const void*>(lifted));
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return -k * (length - rest_length + run()) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
