// Task 2: the forces of all springs and dampers. Handout section 2.
// Declaration, with every argument's meaning and unit:
// common/include/springlab/task2_four_masses.hpp
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

using namespace springlab;

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  // TODO(T2): each spring once, applied to both ends with opposite signs, equations (2.3), (2.4).
  not_implemented_yet(2, __func__, __FILE__, springs, r, v, force);
}
