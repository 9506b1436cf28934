// Task 5: gravity and wind. Handout section 5.
// Declarations, with every argument's meaning and unit:
// common/include/springlab/task5_fabric.hpp
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  // TODO(T5): add m_i g to every particle's force, equation (5.2).
  not_implemented_yet(5, __func__, __FILE__, mass, g, force);
}

void springlab::add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                         Vectors& force) {
  // TODO(T5): add the wind's drag to every particle's force, equation (5.3).
  not_implemented_yet(5, __func__, __FILE__, wind, t, r, v, force);
}
