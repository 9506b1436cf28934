#include "springlab/verlet_support.hpp"

#include <algorithm>
#include <cmath>

namespace springlab {

bool velocity_settled(const Vectors& v_new, const Vectors& v_old, const Vectors& r, double h) {
  const double change = (v_new - v_old).lpNorm<Eigen::Infinity>();
  const double scale = std::max(v_new.lpNorm<Eigen::Infinity>(), r.lpNorm<Eigen::Infinity>() / h);
  return std::isfinite(scale) && change <= 1e-12 * scale;  // an overflow never counts as settled
}

}  // namespace springlab
