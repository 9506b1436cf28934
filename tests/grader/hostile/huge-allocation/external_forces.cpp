// Attack (or a size mistake): add_gravity first allocates 4 GB, more than a test process may
// have (1024 MB). The allocation must fail inside the test (std::bad_alloc, explained as out of
// memory), not take the machine's memory. add_wind is correct, so its tests still pass.
#include "springlab/task5_fabric.hpp"

#include <vector>

using namespace springlab;

void springlab::add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  std::vector<double> scratch(std::size_t(1) << 29, 1.0);  // 4 GB, every page touched
  for (Eigen::Index i = 0; i < force.cols(); ++i)
    force.col(i) += mass[i] * g * scratch[std::size_t(i)];
}

void springlab::add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                         Vectors& force) {
  for (Eigen::Index i = 0; i < force.cols(); ++i)
    force.col(i) += wind.drag() * (wind.velocity(t, r.col(i)) - v.col(i));
}
