// Attack on the memory watch: correct shear springs, but in the sanitized run only (where the
// address-space limit is off, the sanitizers needing terabytes of it) each call first maps 3 GB,
// 256 MB at a time, with MAP_POPULATE so that the kernel fills every page at once (faster than
// touching them, so that the limit is passed well within the time limit even on a busy machine).
// mmap is declared by hand (the policy refuses <sys/mman.h>, not a declaration), and the run is
// told apart at run time.
// The plain run passes; the grader must stop the sanitized run once its resident memory passes
// the limit (1024 MB) and say so.
#include "springlab/task3_shear_springs.hpp"

#include <fstream>
#include <string>

using namespace springlab;

extern "C" void* mmap(void*, unsigned long, int, int, int, long) noexcept;

namespace {

// The sanitized run, told apart at run time: its process maps the sanitizers' run-time. (The
// source policy refuses the macros that would tell it at compile time, and both builds define the
// same ones; what a process can read of itself cannot be hidden from it.)
bool sanitized_run() {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);)
    if (line.find("libasan") != std::string::npos) return true;
  return false;
}

}  // namespace

std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
  constexpr int read_write = 1 | 2, private_anonymous_populate = 0x02 | 0x20 | 0x8000;
  if (sanitized_run())
    for (int chunk = 0; chunk < 12; ++chunk)
      if (mmap(nullptr, std::size_t(256) << 20, read_write, private_anonymous_populate, -1, 0) ==
          reinterpret_cast<void*>(-1))
        break;  // never unmapped
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
