// Task 3: the shear springs of a grid. Handout section 3.
// Declaration, with every argument's meaning and unit:
// common/include/springlab/task3_shear_springs.hpp
#include "springlab/task3_shear_springs.hpp"

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
  // TODO(T3): both diagonals of every grid cell, with the shear family's values, (3.1), (3.2).
  not_implemented_yet(3, __func__, __FILE__, rows, cols, family);
}
