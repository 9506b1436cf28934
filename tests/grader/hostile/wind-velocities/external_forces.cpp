// Not an attack: correct code that uses a documented part of the kit. add_wind asks the wind for
// all the particles' velocities in one call, WindField::velocities (wind.hpp), as the kit's fast
// path does, instead of velocity() one particle at a time. It must link and score full marks.
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  for (Eigen::Index i = 0; i < force.cols(); ++i)
    force.col(i) += mass[i] * g;  // (5.2)
}

void springlab::add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                         Vectors& force) {
  Vectors w(2, r.cols());  // w(t, r_i), (5.4); Vectors stores x and y of each column in turn
  wind.velocities(t, r.data(), int(r.cols()), w.data());
  force += wind.drag() * (w - v);  // (5.3)
}
