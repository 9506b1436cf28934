// Attack: a correct shear_springs, plus a main() of its own (which could replace the test
// program's if the grader linked it into one). The grader must refuse the file.
#include "springlab/task3_shear_springs.hpp"

#include <cstdio>

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
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

int main() {
  std::puts("All tests passed (8 assertions in 8 test cases)");
  return 0;
}
