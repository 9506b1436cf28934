// Attack: shear_springs throws something that is no std::exception (an int), and, for 3x3 grids,
// a type whose destructor throws while the first exception is in flight (std::terminate). The
// tests must fail with the exception explained (or as aborted), never pass.
#include "springlab/task3_shear_springs.hpp"

using namespace springlab;

namespace {
struct Bomb {
  ~Bomb() noexcept(false) { throw 2; }
};
}  // namespace

std::vector<Spring> springlab::shear_springs(int rows, int cols, const SpringFamilyParameters&) {
  if (rows == 3 && cols == 3) {
    Bomb bomb;
    throw 1;  // unwinding destroys bomb, which throws again: std::terminate
  }
  throw 42;
}
