// Attack: a signal the worker never sends itself. The owner of a descriptor opened with O_ASYNC
// gets SIGIO from the kernel whenever I/O becomes possible on it, and SIGIO ends a process that
// does not handle it. So shear_springs makes a pipe, names its parent, the harness that judges
// the test, as the read end's owner, switches on O_ASYNC and writes a byte: kill() is never
// called, yet the harness would die and the test be "not graded". The worker's filter must stop
// the fcntl that names an owner (or switches on O_ASYNC, or picks the signal) and say so.
#include "springlab/task3_shear_springs.hpp"

// Declared by hand: the source policy refuses POSIX headers, not declarations. The values are
// Linux's (x86-64 and arm64 alike).
extern "C" int getppid() noexcept;
extern "C" int pipe(int*) noexcept;
extern "C" int fcntl(int, int, ...);
extern "C" long write(int, const void*, unsigned long);

using namespace springlab;

namespace {

constexpr int set_flags = 4, set_owner = 8;  // F_SETFL, F_SETOWN
constexpr int async = 020000;                // O_ASYNC

void signal_the_parent() {
  int ends[2];
  if (pipe(ends) != 0) return;
  fcntl(ends[0], set_owner, getppid());
  fcntl(ends[0], set_flags, async);
  write(ends[1], "x", 1);
}

}  // namespace

// Otherwise (3.1) done right: only the signal can cost it points.
std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
  signal_the_parent();
  std::vector<Spring> springs;
  for (int i = 0; i + 1 < rows; ++i)
    for (int j = 0; j + 1 < cols; ++j) {
      const int corner = i * cols + j;
      springs.push_back(
          {corner, corner + cols + 1, SpringFamily::shear, family.k, family.b, family.rest_length});
      springs.push_back(
          {corner + 1, corner + cols, SpringFamily::shear, family.k, family.b, family.rest_length});
    }
  return springs;
}
