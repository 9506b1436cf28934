// Backward Euler linearised once per step (Baraff & Witkin 1998):
//   (M − h ∂f/∂v − h² ∂f/∂r) Δv = h (f_n + h ∂f/∂r v_n),
//   v_{n+1} = v_n + Δv,  r_{n+1} = r_n + h v_{n+1}.
// With the spring Jacobians ∂f/∂r = −K(r_n) and ∂f/∂v = −C the matrix is A = M + hC + h²K,
// solved by conjugate gradients (Jacobi preconditioner, warm-started with the last Δv; a sparse
// LDLᵀ factorisation when CG has not converged in 100 iterations).
// Order 1, one evaluation of a(r, v) a step, no step limit on the springs.
//
// - f_n = M a(r_n, v_n) comes from the model, so the forces integrated are the student's and the
//   external forces are included; only the springs enter the Jacobian (external forces are
//   explicit).
// - K drops the negative transverse stiffness of compressed springs (stiffness_block with
//   clamp_compressed): then K is positive semi-definite, A positive definite, and CG applies.
// - A has a fixed sparsity pattern: built once per set of springs and pins, its values refilled
//   each step through precomputed slots (rebuilding from triplets would cost far more than the
//   force evaluation).
// - Pinned particles have no unknowns at all: their rows and columns are left out, so they stay
//   exactly where they are.
#include "integrators.hpp"
#include "spring_matrices.hpp"
#include "springlab/errors.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include <array>

namespace springlab::detail {
namespace {

class ImplicitEuler final : public Integrator {
 public:
  ImplicitEuler() {
    jacobi_.setTolerance(1e-12);
    jacobi_.setMaxIterations(100);
  }
  std::string_view name() const override { return "implicit-euler"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override;
  void restart() override { guess_.resize(0); }

 private:
  void build_pattern(const Model& model);
  void assemble(const Model& model, const Vectors& r, const Vectors& v, double h);
  Eigen::Index slot(int row, int col) const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b, double scale);  // A x = b/scale, |b| = scale

  ModelFingerprint fingerprint_;
  FreeParticles free_{{}};
  Eigen::SparseMatrix<double> matrix_;  // A over the free coordinates (2 per free particle)
  Eigen::VectorXd mass_values_, damping_values_;     // M and C, in matrix_'s value order
  std::vector<std::array<Eigen::Index, 16>> slots_;  // per spring: its K entries, -1 if pinned
  Eigen::VectorXd stiffness_times_v_;                // K v_n over the free coordinates
  Eigen::VectorXd guess_;                            // the last Δv
  // A is solved by CG with a Jacobi preconditioner: at the lab's values A ≈ M(1 + h²ω²) and a few
  // iterations suffice. When h²ω_max² is huge (stiff springs, light masses, long steps) A's
  // condition number grows like it and CG would need thousands of iterations; after 100 the
  // step falls back to a sparse LDLᵀ factorisation of A (its ordering computed once, as the
  // pattern is fixed), whose cost does not depend on the conditioning.
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> jacobi_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct_;
  bool analysed_ = false;
};

// The position of entry (row, col) in matrix_'s values: found once, when the pattern is built.
Eigen::Index ImplicitEuler::slot(int row, int col) const {
  const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
  const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
  return std::lower_bound(begin, end, row) - matrix_.innerIndexPtr();
}

void ImplicitEuler::build_pattern(const Model& model) {
  free_ = FreeParticles(model.pinned);
  const int n = 2 * free_.size();
  // Each spring couples the two coordinates of each free end with each other: four 2×2 blocks.
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    entries.emplace_back(i, i, 0.0);
  for (const Spring& s : model.springs)
    for (int a : {free_.index[std::size_t(s.p)], free_.index[std::size_t(s.q)]})
      for (int b : {free_.index[std::size_t(s.p)], free_.index[std::size_t(s.q)]})
        if (a >= 0 && b >= 0)
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
              entries.emplace_back(2 * a + i, 2 * b + j, 0.0);
  matrix_.resize(n, n);
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  analysed_ = false;

  mass_values_.setZero(matrix_.nonZeros());
  damping_values_.setZero(matrix_.nonZeros());
  for (int j = 0; j < free_.size(); ++j)
    for (int i = 0; i < 2; ++i)
      mass_values_[slot(2 * j + i, 2 * j + i)] = model.mass[free_.particle[std::size_t(j)]];
  slots_.clear();
  for (const Spring& s : model.springs) {
    const int p = free_.index[std::size_t(s.p)], q = free_.index[std::size_t(s.q)];
    std::array<Eigen::Index, 16> spring_slots;
    spring_slots.fill(-1);
    // Blocks in the order pp, qq, pq, qp; the damper is b·I in each (with sign −1 off the
    // diagonal blocks), the stiffness ±B.
    const std::array<std::array<int, 2>, 4> blocks{{{p, p}, {q, q}, {p, q}, {q, p}}};
    for (std::size_t k = 0; k < 4; ++k) {
      const auto [a, b] = blocks[k];
      if (a < 0 || b < 0) continue;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          spring_slots[4 * k + std::size_t(2 * i + j)] = slot(2 * a + i, 2 * b + j);
      for (int i = 0; i < 2; ++i)
        damping_values_[slot(2 * a + i, 2 * b + i)] += k < 2 ? s.b : -s.b;
    }
    slots_.push_back(spring_slots);
  }
  guess_.resize(0);
}

void ImplicitEuler::assemble(const Model& model, const Vectors& r, const Vectors& v, double h) {
  Eigen::Map<Eigen::VectorXd> values(matrix_.valuePtr(), matrix_.nonZeros());
  values = mass_values_ + h * damping_values_;
  stiffness_times_v_.setZero(2 * free_.size());
  for (std::size_t n = 0; n < model.springs.size(); ++n) {
    const Spring& s = model.springs[n];
    const Eigen::Matrix2d b =
        stiffness_block(r.col(s.p) - r.col(s.q), s.k, s.rest_length, /*clamp_compressed=*/true);
    const std::array<Eigen::Index, 16>& where = slots_[n];
    for (std::size_t k = 0; k < 4; ++k) {
      const double sign = k < 2 ? h * h : -h * h;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          if (const Eigen::Index at = where[4 * k + std::size_t(2 * i + j)]; at >= 0)
            values[at] += sign * b(i, j);
    }
    const Vec2 pull = b * (v.col(s.p) - v.col(s.q));
    if (const int p = free_.index[std::size_t(s.p)]; p >= 0)
      stiffness_times_v_.segment<2>(2 * p) += pull;
    if (const int q = free_.index[std::size_t(s.q)]; q >= 0)
      stiffness_times_v_.segment<2>(2 * q) -= pull;
  }
}

Eigen::VectorXd ImplicitEuler::solve(const Eigen::VectorXd& rhs, double scale) {
  // Solved for Δv/scale, so that CG's tolerance is relative to a right-hand side of norm 1.
  const Eigen::VectorXd b = rhs / scale;
  jacobi_.compute(matrix_);
  const Eigen::VectorXd x = jacobi_.solveWithGuess(b, guess_ / scale);
  if (jacobi_.info() == Eigen::Success) return x;
  if (!analysed_) direct_.analyzePattern(matrix_), analysed_ = true;
  direct_.factorize(matrix_);
  if (direct_.info() != Eigen::Success)
    throw StepFailed("the implicit step's matrix M + hC + h^2 K could not be factorised");
  return direct_.solve(b);
}

void ImplicitEuler::step(const Model& model, double h, Vectors& r, Vectors& v) {
  if (fingerprint_.changed(model)) build_pattern(model);
  if (free_.size() == 0) return;
  const Vectors& a = model.acceleration(r, v);
  Eigen::VectorXd rhs(2 * free_.size());
  for (int j = 0; j < free_.size(); ++j) {
    const int i = free_.particle[std::size_t(j)];
    rhs.segment<2>(2 * j) = h * model.mass[i] * a.col(i);  // h f_n
  }
  assemble(model, r, v, h);
  rhs -= h * h * stiffness_times_v_;
  if (guess_.size() != rhs.size()) guess_.setZero(rhs.size());
  // Solved for Δv / |rhs|: CG judges convergence by squared norms, which underflow once a
  // decaying motion reaches 1e-155 and would stop it before its first iteration.
  const double scale = rhs.norm();
  const Eigen::VectorXd dv =
      scale == 0.0 ? Eigen::VectorXd::Zero(rhs.size()).eval() : scale * solve(rhs, scale);
  guess_ = dv;
  for (int j = 0; j < free_.size(); ++j) {
    const int i = free_.particle[std::size_t(j)];
    v.col(i) += dv.segment<2>(2 * j);
    r.col(i) += h * v.col(i);
  }
}

}  // namespace

std::unique_ptr<Integrator> make_implicit_euler() {
  return std::make_unique<ImplicitEuler>();
}

}  // namespace springlab::detail
