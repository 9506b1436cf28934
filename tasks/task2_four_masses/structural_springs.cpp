// Task 2: the structural springs of a grid. Handout section 2.
// Declaration, with every argument's meaning and unit:
// common/include/springlab/task2_four_masses.hpp
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

std::vector<Spring> springlab::structural_springs(int rows, int cols,
                                                  const SpringFamilyParameters& family) {
  // TODO(T2): one spring per pair of horizontal or vertical neighbours, equations (2.1), (2.2).
  not_implemented_yet(2, __func__, __FILE__, rows, cols, family);
}
