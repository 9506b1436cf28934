// Attack: one line of plain C++ that makes a 300 MB object file (the array is initialised, so it
// is stored in the object), to fill the grader's disk.
#include "springlab/task5_fabric.hpp"

using namespace springlab;

char ballast[300000000] = {7};  // NOLINT: the attack

void springlab::hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  for (std::size_t i = 0; i < pinned.size(); ++i)
    if (pinned[i]) acceleration.col(Eigen::Index(i)).setZero();  // (5.5)
}
