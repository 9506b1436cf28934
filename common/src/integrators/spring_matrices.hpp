// The derivatives of the spring and damper forces (lecture: Hooke + damper F = -b(v_p - v_q)),
// shared by the implicit integrators and the stability theory. Private to the core's libraries
// (springlab_scenes and springlab_core, common/CMakeLists.txt).
#pragma once

#include "springlab/parallel.hpp"
#include "springlab/types.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace springlab::detail {

/// B = k [ûûᵀ + (1 − ℓ0/L)(I − ûûᵀ)], the Hessian of ½k(L − ℓ0)² with respect to d = r_p − r_q,
/// so ∂F_pq/∂r_p = −B and ∂F_pq/∂r_q = +B. With `clamp_compressed` the transverse factor
/// (1 − ℓ0/L), negative for a compressed spring, is raised to 0: B stays positive semi-definite,
/// which keeps the implicit system positive definite. L = 0 gives B = 0: the kit's spring force is
/// zero there (no direction to push along), and so is its derivative.
/// Inline: the implicit step computes one for every spring at every step.
inline Eigen::Matrix2d stiffness_block(const Vec2& d, double k, double rest_length,
                                       bool clamp_compressed) {
  const double length = d.norm();
  if (length == 0.0) return Eigen::Matrix2d::Zero();
  const Vec2 u = d / length;
  const Eigen::Matrix2d along = u * u.transpose();
  double across = 1.0 - rest_length / length;
  if (clamp_compressed && across < 0.0) across = 0.0;
  return k * (along + across * (Eigen::Matrix2d::Identity() - along));
}

/// The free (unpinned) particles numbered 0 … size()-1 in their original order.
struct FreeParticles {
  explicit FreeParticles(const std::vector<bool>& pinned);
  std::vector<int> index;     ///< particle → free index, -1 if pinned
  std::vector<int> particle;  ///< free index → particle
  int size() const { return int(particle.size()); }
};

/// Σ over dampers of b (e_p − e_q)(e_p − e_q)ᵀ on the free particles: the damping matrix of one
/// coordinate (dampers act alike on x and y). A damper to a pinned particle adds only to the
/// free end's diagonal, as the pinned end never moves.
Eigen::SparseMatrix<double> scalar_damping(const std::vector<Spring>& springs,
                                           const FreeParticles& free);

}  // namespace springlab::detail

namespace springlab::detail {

/// The vectors conjugate_gradients works with, kept by its caller to reuse their storage.
struct ConjugateGradientStorage {
  Vectors residual, direction, product, preconditioned;
  long products = 0;  // every multiply of every solve: the integrators' SolverWork
};

/// Particles [begin, end) of m (one column each) as one flat vector of 2 (end − begin) numbers:
/// a block of for_blocks or sum_blocks, which Eigen then vectorises whole.
inline Eigen::Map<Eigen::VectorXd> flat(Vectors& m, long begin, long end) {
  return {m.data() + 2 * begin, 2 * (end - begin)};
}
inline Eigen::Map<const Eigen::VectorXd> flat(const Vectors& m, long begin, long end) {
  return {m.data() + 2 * begin, 2 * (end - begin)};
}

/// Solves A x = b for a symmetric positive definite A given only as a product,
/// multiply(x, product) setting product = A x, by conjugate gradients with the diagonal
/// preconditioner inverse_diagonal (1/A_ii; 0 for a coordinate held at zero, where b and
/// every product must be 0 too). The same iteration as Eigen's ConjugateGradient: it stops when
/// |b − A x| < tolerance |b| or after max_iterations, starting from x as given. (Eigen's solver
/// runs matrix-free only through a wrapper type that specialises Eigen::internal's traits and
/// product and a preconditioner class of our own, on flat vectors: more code, reaching into
/// Eigen's internals, than these few lines on the 2×n vectors the integrators hold.)
/// The vector work is split over threads by particles (for_blocks), and every dot product is
/// summed in sum_blocks' fixed blocks: the same bits for any thread count.
/// b, x: one column per particle. False when it has not converged.
template <class Multiply>
bool conjugate_gradients(Multiply&& multiply, const Vectors& inverse_diagonal, const Vectors& b,
                         Vectors& x, double tolerance, int max_iterations,
                         ConjugateGradientStorage& cg) {
  const long n = long(b.cols());
  const double b_norm2 =
      sum_blocks(n, [&](long begin, long end) { return flat(b, begin, end).squaredNorm(); });
  if (b_norm2 == 0.0) {
    x.setZero(b.rows(), n);
    return true;
  }
  const double threshold =
      std::max(tolerance * tolerance * b_norm2, std::numeric_limits<double>::min());
  Vectors &r = cg.residual, &d = cg.direction, &ad = cg.product, &z = cg.preconditioned;
  r.resize(2, n);
  d.resize(2, n);
  z.resize(2, n);
  // z = D⁻¹ r, and r · z.
  const auto precondition = [&] {
    return sum_blocks(n, [&](long begin, long end) {
      flat(z, begin, end) = flat(inverse_diagonal, begin, end).cwiseProduct(flat(r, begin, end));
      return flat(r, begin, end).cwiseProduct(flat(z, begin, end)).sum();
    });
  };
  multiply(x, ad);
  ++cg.products;
  double residual_norm2 = sum_blocks(n, [&](long begin, long end) {
    flat(r, begin, end) = flat(b, begin, end) - flat(ad, begin, end);
    return flat(r, begin, end).squaredNorm();
  });
  if (residual_norm2 < threshold) return true;
  double rz = precondition();
  for_blocks(n, [&](long begin, long end) { flat(d, begin, end) = flat(z, begin, end); });
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    multiply(d, ad);
    ++cg.products;
    const double alpha = rz / sum_blocks(n, [&](long begin, long end) {
                           return flat(d, begin, end).cwiseProduct(flat(ad, begin, end)).sum();
                         });
    residual_norm2 = sum_blocks(n, [&](long begin, long end) {
      flat(x, begin, end) += alpha * flat(d, begin, end);
      flat(r, begin, end) -= alpha * flat(ad, begin, end);
      return flat(r, begin, end).squaredNorm();
    });
    if (residual_norm2 < threshold) return true;
    const double rz_old = rz;
    rz = precondition();
    const double beta = rz / rz_old;
    for_blocks(n, [&](long begin, long end) {
      flat(d, begin, end) = flat(z, begin, end) + beta * flat(d, begin, end);
    });
  }
  return std::sqrt(residual_norm2 / b_norm2) <= tolerance;
}

}  // namespace springlab::detail

namespace springlab {
struct Model;
}

namespace springlab::detail {

/// Remembers what the damping and mass matrices of a model were built from (each spring's ends
/// and b, the masses, the pins), so an integrator can rebuild them when the viewer changes any.
class ModelFingerprint {
 public:
  /// True the first time and whenever `model` differs from the last call's; then remembers it.
  bool changed(const Model& model);

 private:
  bool known_ = false;
  std::vector<Spring> springs_;
  Eigen::VectorXd mass_;
  std::vector<bool> pinned_;
};

}  // namespace springlab::detail
