// Task 5: pinned particles. Handout section 5.
// Declaration, with every argument's meaning and unit:
// common/include/springlab/task5_fabric.hpp
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  // TODO(T5): a pinned particle never moves, equation (5.5).
  not_implemented_yet(5, __func__, __FILE__, pinned, acceleration);
}
