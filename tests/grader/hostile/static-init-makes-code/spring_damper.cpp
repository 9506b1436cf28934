// Attack: plain C++ that puts machine code lifted from a compiled reference (here "xor eax, eax;
// ret", the point being where it runs) into a page-aligned array and makes it executable with
// mprotect, declared by hand (no header needed), from a static initialiser: initialisers used to
// run while the worker loaded the library, before it forbade executable memory. spring_force
// then calls into the array.
#include "springlab/task1_two_masses.hpp"

using namespace springlab;

extern "C" int mprotect(void* address, unsigned long length, int protection);

namespace {

alignas(4096) unsigned char lifted[4096] = {0x31, 0xc0, 0xc3};
const bool executable = mprotect(lifted, sizeof lifted, 1 | 2 | 4) == 0;  // read, write, exec

}  // namespace

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  const int zero = executable ? reinterpret_cast<int (*)()>(static_cast<void*>(lifted))() : 0;
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return -k * (length - rest_length + zero) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
