// Task 5: gravity and wind. Handout section 5.
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  for (Eigen::Index i = 0; i < force.cols(); ++i)
    force.col(i) += mass[i] * g;  // (5.2)
}

void springlab::add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                         Vectors& force) {
  for (Eigen::Index i = 0; i < force.cols(); ++i)
    force.col(i) += wind.drag() * (wind.velocity(t, r.col(i)) - v.col(i));  // (5.3)
}
