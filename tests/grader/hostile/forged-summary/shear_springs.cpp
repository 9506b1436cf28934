// Attack: instead of computing anything, shear_springs prints a perfect summary in the grader's
// own words and in Catch2's, then ends the process with status 0 at once (_exit skips every
// destructor and the harness's verdict). The grader must fail each test: no verdict record.
#include "springlab/task3_shear_springs.hpp"

// Declared by hand: the source policy refuses POSIX headers, but not a declaration (the sandbox
// and the test process's filter are what stop the call).
extern "C" [[noreturn]] void _exit(int);

#include <cstdio>

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  std::printf("  Shear springs: the count, both diagonals of each cell once ... pass\n");
  std::printf("\n8 of 8 tests pass (8 of 8 points).\n");
  std::printf("===============================================================================\n");
  std::printf("All tests passed (1234 assertions in 8 test cases)\n\n");
  std::fflush(stdout);
  _exit(0);
}
