// Task 5: the bend springs of a fabric. Handout section 5.
#include "springlab/task5_fabric.hpp"
#include "helpers.hpp"

using namespace springlab;

std::vector<Spring> springlab::bend_springs(int rows, int cols,
                                            const SpringFamilyParameters& family) {
  const auto index = [cols](int row, int col) { return row * cols + col; };  // (2.1)
  std::vector<Spring> springs;
  const auto join = [&](int p, int q) {
    springs.push_back({p, q, SpringFamily::bend, family.k, family.b, family.rest_length});
  };
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) {  // (5.1): two places right and two places down
      if (col + 2 < cols) join(index(row, col), index(row, col + 2));
      if (row + 2 < rows) join(index(row, col), index(row + 2, col));
    }
  return springs;
}
