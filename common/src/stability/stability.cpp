#include "springlab/stability.hpp"

#include "integrators/spring_matrices.hpp"
#include "springlab/eigen_solvers.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"
#include "springlab/verlet_support.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace springlab {

solvers::SymmetricEigen solvers::symmetric_eigen(const Eigen::MatrixXd& m, bool vectors) {
  return SymmetricEigen(m, vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
}

solvers::GeneralEigen solvers::general_eigen(const Eigen::MatrixXd& m, bool vectors) {
  return GeneralEigen(m, vectors);
}

namespace {

// Adds the 2×2 block B of a spring between p and q: +B on the diagonal blocks, -B off them.
void add_pair_block(Eigen::MatrixXd& matrix, int p, int q, const Eigen::Matrix2d& block) {
  matrix.block<2, 2>(2 * p, 2 * p) += block;
  matrix.block<2, 2>(2 * q, 2 * q) += block;
  matrix.block<2, 2>(2 * p, 2 * q) -= block;
  matrix.block<2, 2>(2 * q, 2 * p) -= block;
}

}  // namespace

LinearModel linearise(const std::vector<Spring>& springs, const Vectors& r,
                      const Eigen::VectorXd& mass, const std::vector<bool>& pinned) {
  const int n = static_cast<int>(r.cols());
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Eigen::MatrixXd damping = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  for (const Spring& s : springs) {
    // Hessian of ½k(|d| - ℓ0)²: stiff along the spring, (1 - ℓ0/L)·k across it.
    const Eigen::Matrix2d hessian =
        detail::stiffness_block(r.col(s.p) - r.col(s.q), s.k, s.rest_length, false);
    add_pair_block(stiffness, s.p, s.q, hessian);
    add_pair_block(damping, s.p, s.q, s.b * Eigen::Matrix2d::Identity());
  }
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!pinned[i]) free.insert(free.end(), {2 * i, 2 * i + 1});
  LinearModel model;
  model.stiffness = stiffness(free, free);
  model.damping = damping(free, free);
  model.mass.resize(Eigen::Index(free.size()));
  for (std::size_t j = 0; j < free.size(); ++j)
    model.mass[Eigen::Index(j)] = mass[free[j] / 2];
  return model;
}

double highest_frequency(const LinearModel& model) {
  if (model.mass.size() == 0) return 0.0;  // every particle pinned: nothing moves
  const Eigen::VectorXd scale = model.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * model.stiffness * scale.asDiagonal();
  return std::sqrt(std::max(0.0, solvers::symmetric_eigen(scaled, false).eigenvalues().maxCoeff()));
}

Eigen::MatrixXd system_matrix(const LinearModel& model) {
  const Eigen::Index n = model.mass.size();
  const Eigen::VectorXd inverse_mass = model.mass.cwiseInverse();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  a.bottomLeftCorner(n, n) = -(inverse_mass.asDiagonal() * model.stiffness);
  a.bottomRightCorner(n, n) = -(inverse_mass.asDiagonal() * model.damping);
  return a;
}

Eigen::VectorXcd balanced_eigenvalues(Eigen::MatrixXd a) {
  // Each row and column pair is scaled by a power of 2 until their off-diagonal norms are within a
  // factor of 2 of each other (Numerical Recipes' "balanc", LAPACK's dgebal without permutations).
  constexpr double radix = 2.0;
  for (bool done = false; !done;) {
    done = true;
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      double column = a.col(i).cwiseAbs().sum() - std::abs(a(i, i));
      const double row = a.row(i).cwiseAbs().sum() - std::abs(a(i, i));
      if (column == 0.0 || row == 0.0) continue;
      const double before = column + row;
      double f = 1.0;
      while (column < row / radix)
        f *= radix, column *= radix * radix;
      while (column > row * radix)
        f /= radix, column /= radix * radix;
      if ((column + row) / f < 0.95 * before) {  // column is now f^2 times the old one
        done = false;
        a.row(i) /= f;
        a.col(i) *= f;
      }
    }
  }
  return solvers::general_eigen(a, false).eigenvalues();
}

Eigen::VectorXcd system_eigenvalues(const LinearModel& model) {
  return balanced_eigenvalues(system_matrix(model));
}

double explicit_euler_growth_factor(const LinearModel& model, double h) {
  if (model.mass.size() == 0) return 0.0;
  return polynomial_growth_factor(deforming_eigenvalues(model), "explicit-euler", h);
}

double explicit_euler_critical_step(const LinearModel& model) {
  if (model.mass.size() == 0) return std::numeric_limits<double>::infinity();
  return polynomial_critical_step(deforming_eigenvalues(model), "explicit-euler");
}

double verlet_critical_step(const LinearModel& model) {
  return 2.0 / highest_frequency(model);
}

double fastest_damping_rate(const LinearModel& model) {
  if (model.mass.size() == 0) return 0.0;
  const Eigen::VectorXd scale = model.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd c = scale.asDiagonal() * model.damping * scale.asDiagonal();
  return std::max(0.0, solvers::symmetric_eigen(c, false).eigenvalues().maxCoeff());
}

double verlet_iteration_factor() {
  return std::pow(1e-12, 1.0 / verlet_max_iterations);
}

double verlet_iteration_limit(const LinearModel& model) {
  const double c = fastest_damping_rate(model);
  return c > 0.0 ? 2.0 * verlet_iteration_factor() / c : std::numeric_limits<double>::infinity();
}

void add_drag(LinearModel& model, double drag) {
  model.damping.diagonal().array() += drag;
  model.drag = Eigen::VectorXd::Constant(model.mass.size(), drag);
}

double highest_frequency_bound(const std::vector<Spring>& springs, const Vectors& r,
                               const Eigen::VectorXd& mass, const std::vector<bool>& pinned) {
  // Row i of K gets |B| from the spring's diagonal block and, if the other end is free, |B|
  // again from the off-diagonal one.
  Vectors row_sums = Vectors::Zero(2, r.cols());
  for (const Spring& s : springs) {
    const Eigen::Matrix2d b =
        detail::stiffness_block(r.col(s.p) - r.col(s.q), s.k, s.rest_length, false).cwiseAbs();
    const Vec2 sums = b.rowwise().sum();
    row_sums.col(s.p) += (pinned[std::size_t(s.q)] ? 1.0 : 2.0) * sums;
    row_sums.col(s.q) += (pinned[std::size_t(s.p)] ? 1.0 : 2.0) * sums;
  }
  double largest = 0.0;
  for (Eigen::Index i = 0; i < r.cols(); ++i)
    if (!pinned[std::size_t(i)]) largest = std::max(largest, row_sums.col(i).maxCoeff() / mass[i]);
  return std::sqrt(largest);
}

double damping_rate_bound(const std::vector<Spring>& springs, const Eigen::VectorXd& mass,
                          const std::vector<bool>& pinned) {
  Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(mass.size());
  for (const Spring& s : springs) {
    row_sums[s.p] += (pinned[std::size_t(s.q)] ? 1.0 : 2.0) * s.b;
    row_sums[s.q] += (pinned[std::size_t(s.p)] ? 1.0 : 2.0) * s.b;
  }
  double largest = 0.0;
  for (Eigen::Index i = 0; i < mass.size(); ++i)
    if (!pinned[std::size_t(i)]) largest = std::max(largest, row_sums[i] / mass[i]);
  return largest;
}

Scene scene_at_rest(const SceneParameters& p, const Implementation& impl) {
  SceneParameters still = p;
  still.displacement = Vec2::Zero();
  return build_scene(still, impl);
}

LinearModel linearise(const Scene& scene) {
  const Particles& particles = scene.particles;
  LinearModel model =
      linearise(scene.springs, particles.position, particles.mass, particles.pinned);
  const WindParameters& wind = scene.parameters.wind;
  if (wind.enabled) add_drag(model, wind.drag);
  return model;
}

LinearModel linearise_at_rest(const SceneParameters& p, const Implementation& impl) {
  return linearise(scene_at_rest(p, impl));
}

}  // namespace springlab
