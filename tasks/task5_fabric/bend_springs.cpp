// Task 5: the bend springs of a fabric. Handout section 5.
// Declaration, with every argument's meaning and unit:
// common/include/springlab/task5_fabric.hpp
#include "springlab/task5_fabric.hpp"

using namespace springlab;

std::vector<Spring> springlab::bend_springs(int rows, int cols,
                                            const SpringFamilyParameters& family) {
  // TODO(T5): the springs of equation (5.1), two places right and two places down, each once.
  not_implemented_yet(5, __func__, __FILE__, rows, cols, family);
}
