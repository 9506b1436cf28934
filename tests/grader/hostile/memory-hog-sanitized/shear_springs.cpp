// Attack on the memory watch: correct shear springs, but in the sanitized build only (where the
// address-space limit is off, the sanitizers needing terabytes of it) each call first maps 3 GB,
// 256 MB at a time, with MAP_POPULATE so that the kernel fills every page at once (faster than
// touching them, so that the limit is passed well within the time limit even on a busy machine).
// The plain run passes; the grader must stop the sanitized run once its resident memory passes
// the limit (1024 MB) and say so.
#include "springlab/task3_shear_springs.hpp"

#include <sys/mman.h>

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
#if defined(__SANITIZE_ADDRESS__)
  for (int chunk = 0; chunk < 12; ++chunk)
    if (mmap(nullptr, std::size_t(256) << 20, PROT_READ | PROT_WRITE,
             MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0) == MAP_FAILED)
      break;  // never unmapped
#endif
  const auto index = [cols](int row, int col) { return row * cols + col; };
  std::vector<Spring> springs;
  for (int row = 0; row + 1 < rows; ++row)
    for (int col = 0; col + 1 < cols; ++col) {
      springs.push_back({index(row, col), index(row + 1, col + 1), SpringFamily::shear, family.k,
                         family.b, family.rest_length});
      springs.push_back({index(row, col + 1), index(row + 1, col), SpringFamily::shear, family.k,
                         family.b, family.rest_length});
    }
  return springs;
}
