// Not an attack: a plain mistake. bend_springs reserves rows (cols - 2) + cols (rows - 2) springs
// without (5.1)'s max(., 0), so a single row's negative count becomes a huge size and reserve()
// throws std::length_error. The feedback must name that type (not the harness's relay) and the
// grid the call was given (issue 38).
#include "springlab/task5_fabric.hpp"

#include <cstddef>

using namespace springlab;

std::vector<Spring> springlab::bend_springs(int rows, int cols, const SpringFamilyParameters& p) {
  std::vector<Spring> springs;
  springs.reserve(std::size_t(rows * (cols - 2) + cols * (rows - 2)));
  const auto index = [cols](int i, int j) { return i * cols + j; };
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      if (j + 2 < cols)
        springs.push_back(
            {index(i, j), index(i, j + 2), SpringFamily::bend, p.k, p.b, p.rest_length});
      if (i + 2 < rows)
        springs.push_back(
            {index(i, j), index(i + 2, j), SpringFamily::bend, p.k, p.b, p.rest_length});
    }
  return springs;
}
