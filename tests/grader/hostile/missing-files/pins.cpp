// Task 5: pinned particles. Handout section 5.
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  for (std::size_t i = 0; i < pinned.size(); ++i)
    if (pinned[i]) acceleration.col(Eigen::Index(i)).setZero();  // (5.5)
}
