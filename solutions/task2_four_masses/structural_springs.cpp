// Task 2: the structural springs of a grid. Handout section 2.
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

std::vector<Spring> springlab::structural_springs(int rows, int cols,
                                                  const SpringFamilyParameters& family) {
  const auto index = [cols](int row, int col) { return row * cols + col; };  // (2.1)
  std::vector<Spring> springs;
  springs.reserve(std::size_t(rows * (cols - 1) + cols * (rows - 1)));
  const auto join = [&](int p, int q) {
    springs.push_back({p, q, SpringFamily::structural, family.k, family.b, family.rest_length});
  };
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) {  // (2.2): right and down, so each pair once
      if (col + 1 < cols) join(index(row, col), index(row, col + 1));
      if (row + 1 < rows) join(index(row, col), index(row + 1, col));
    }
  return springs;
}
