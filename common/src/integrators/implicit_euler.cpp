// Backward Euler linearised once per step (Baraff & Witkin 1998):
//   (M − h ∂f/∂v − h² ∂f/∂r) Δv = h (f_n + h ∂f/∂r v_n),
//   v_{n+1} = v_n + Δv,  r_{n+1} = r_n + h v_{n+1}.
// With the spring Jacobians ∂f/∂r = −K(r_n) and ∂f/∂v = −C the matrix is A = M + hC + h²K,
// solved by conjugate gradients (Jacobi preconditioner, warm-started with Δv extrapolated from
// the last two steps; a sparse LDLᵀ factorisation when CG has not converged in 100 iterations).
// Order 1, one evaluation of a(r, v) a step, no step limit on the springs.
//
// - f_n = M a(r_n, v_n) comes from the model, so the forces integrated are the student's and the
//   external forces are included; only the springs enter the Jacobian (external forces are
//   explicit).
// - K drops the negative transverse stiffness of compressed springs (stiffness_block with
//   clamp_compressed): then K is positive semi-definite, A positive definite, and CG applies.
// - CG never sees A as a matrix: each spring's 2×2 block S = hb I + h²B (B = stiffness_block) is
//   computed once a step, and A x = M x + Σ_springs S (x_p − x_q), added to p and taken from q.
//   That product reads 3 numbers and the two ends a spring where a stored sparse A holds 16
//   entries a spring with their indices: about 4 times faster, and no matrix to fill. (At the lab's
//   values CG needs a few iterations, so the step costs a handful of force evaluations; see
//   tests/benchmarks/README.md.) The sparse matrix is built only for the LDLᵀ fallback.
// - On two threads (parallel.hpp) the work per spring is split by springs and the rest by
//   particles: each particle gathers its springs' terms, in the springs' order, where one thread
//   scatters each spring's to both ends. The same additions in the same order: the same bits for
//   any thread count.
// - Pinned particles have no unknowns: their Δv is held at zero in every CG vector (A x is
//   zeroed there, and so is the preconditioner), so they stay exactly where they are.
#include "integrators/integrators.hpp"
#include "integrators/spring_matrices.hpp"
#include "springlab/errors.hpp"
#include "springlab/memory_budget.hpp"
#include "springlab/parallel.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace springlab::detail {
namespace {

class ImplicitEuler final : public Integrator {
 public:
  std::string_view name() const override { return "implicit-euler"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override;
  void restart() override {
    guess_.resize(2, 0);
    previous_.resize(2, 0);
  }
  SolverWork solver_work() const override { return {cg_.products, factorisations_}; }

 private:
  // S = hb I + h²B of one spring, symmetric: what the spring adds to A's pp and qq blocks and
  // takes from its pq and qp blocks; with the spring's ends, so that A x reads one array.
  struct Block {
    double xx, xy, yy;
    int p, q;
  };

  void prepare(const Model& model);
  void linearise(const Model& model, const Vectors& r, const Vectors& v, double h);
  void multiply(const Model& model, const Vectors& x, Vectors& product) const;  // A x
  // For a gather: calls each(s, sign) for each spring s of particle i in the springs' order, with
  // sign +1 where i is its first end and −1 where it is its second. (a + (−1)·t is a − t to the
  // bit, without a branch the processor could not predict.)
  template <class Each>
  void for_springs_of(long i, Each&& each) const;
  // per_spring_.col(s) = vector_of(s) for each of `springs` springs, split over threads.
  template <class VectorOf>
  void fill_per_spring(long springs, VectorOf&& vector_of) const;
  Vectors solve_directly(const Model& model, const Vectors& r, double h, const Vectors& b);
  void build_pattern(const Model& model);
  Eigen::Index slot(int row, int col) const;

  ModelFingerprint fingerprint_;
  FreeParticles free_{{}};
  std::vector<int> pinned_;    // the pinned particles
  std::vector<Block> blocks_;  // per spring, at r_n
  // On two threads, a vector per spring for the gathers: its pull B (v_p − v_q) in linearise,
  // its S (x_p − x_q) in multiply.
  mutable Vectors per_spring_;
  // Each particle's springs in the springs' order, spring s as 2s where the particle is its
  // first end and 2s + 1 where it is its second: incident_[incident_start_[i] …
  // incident_start_[i + 1]) are particle i's (32 bits: prepare refuses 2^31 springs or more).
  std::vector<long> incident_start_;
  std::vector<std::uint32_t> incident_;
  Vectors inverse_diagonal_;   // Jacobi preconditioner: 1 / A's diagonal, 0 where pinned
  Vectors stiffness_times_v_;  // K v_n
  Vectors rhs_, solution_;     // h (f_n − h K v_n) / |…|, Δv / |…|
  Vectors guess_, previous_;   // the last two steps' Δv (empty after a restart)
  ConjugateGradientStorage cg_;
  // The fallback: A as a sparse matrix over the free coordinates (2 per free particle), with a
  // fixed pattern built on first use; its values refilled through precomputed slots. When
  // h²ω_max² is huge (stiff springs, light masses, long steps) A's condition number grows like
  // it and CG would need thousands of iterations; the factorisation's cost does not depend on it.
  bool pattern_built_ = false;
  Eigen::SparseMatrix<double> matrix_;
  Eigen::VectorXd mass_values_, damping_values_;     // M and C, in matrix_'s value order
  std::vector<std::array<Eigen::Index, 16>> slots_;  // per spring: its K entries, -1 if pinned
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct_;
  bool analysed_ = false;
  long factorisations_ = 0;
};

void ImplicitEuler::prepare(const Model& model) {
  free_ = FreeParticles(model.pinned);
  pinned_.clear();
  for (std::size_t i = 0; i < model.pinned.size(); ++i)
    if (model.pinned[i]) pinned_.push_back(int(i));
  pattern_built_ = false;
  const long n = long(model.mass.size());
  incident_start_.assign(std::size_t(n) + 1, 0);
  for (const Spring& s : model.springs)
    ++incident_start_[std::size_t(s.p) + 1], ++incident_start_[std::size_t(s.q) + 1];
  for (std::size_t i = 0; i < std::size_t(n); ++i)
    incident_start_[i + 1] += incident_start_[i];
  // Codes 2s and 2s + 1 in 32 bits: no scene that fits in memory comes near, but say so if one
  // does.
  if (model.springs.size() >= (std::size_t(1) << 31))
    throw InvalidParameter("springs", std::to_string(model.springs.size()),
                           "fewer than 2^31 for implicit-euler");
  incident_.resize(2 * model.springs.size());
  std::vector<long> next(incident_start_.begin(), incident_start_.end() - 1);
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    incident_[std::size_t(next[std::size_t(model.springs[s].p)]++)] = std::uint32_t(2 * s);
    incident_[std::size_t(next[std::size_t(model.springs[s].q)]++)] = std::uint32_t(2 * s + 1);
  }
  restart();
}

template <class VectorOf>
void ImplicitEuler::fill_per_spring(long springs, VectorOf&& vector_of) const {
  per_spring_.resize(2, springs);
  for_blocks(springs, [&](long begin, long end) {
    for (long s = begin; s < end; ++s)
      per_spring_.col(s) = vector_of(s);
  });
}

template <class Each>
void ImplicitEuler::for_springs_of(long i, Each&& each) const {
  for (long k = incident_start_[std::size_t(i)]; k < incident_start_[std::size_t(i) + 1]; ++k) {
    const std::uint32_t code = incident_[std::size_t(k)];
    each(long(code / 2), 1.0 - 2.0 * double(code % 2));
  }
}

void ImplicitEuler::linearise(const Model& model, const Vectors& r, const Vectors& v, double h) {
  const long n = long(r.cols()), springs = long(model.springs.size());
  blocks_.resize(std::size_t(springs));
  // Spring i's block S, kept, and its pull B (v_p − v_q), returned.
  const auto linearise_spring = [&](long i) -> Vec2 {
    const Spring& s = model.springs[std::size_t(i)];
    // stiffness_block with clamp_compressed, B = k [(1 − a) û ûᵀ + a I], a = max(0, 1 − ℓ0/L),
    // with one square root and one division.
    const Vec2 d = r.col(s.p) - r.col(s.q);
    const double length2 = d.squaredNorm();
    Eigen::Matrix2d b = Eigen::Matrix2d::Zero();
    if (length2 > 0.0) {
      const double inverse_length = 1.0 / std::sqrt(length2);
      const double across = std::max(0.0, 1.0 - s.rest_length * inverse_length);
      b = (s.k * (1.0 - across) * inverse_length * inverse_length) * (d * d.transpose());
      b.diagonal().array() += s.k * across;
    }
    blocks_[std::size_t(i)] = {h * s.b + h * h * b(0, 0), h * h * b(0, 1),
                               h * s.b + h * h * b(1, 1), s.p, s.q};
    return b * (v.col(s.p) - v.col(s.q));
  };
  // K v_n and A's diagonal M + Σ (S_xx, S_yy) over each particle's springs.
  stiffness_times_v_.setZero(2, n);
  Vectors diagonal = model.mass.transpose().replicate<2, 1>();
  if (splits(n)) {
    fill_per_spring(springs, linearise_spring);
    for_blocks(n, [&](long begin, long end) {
      for (long i = begin; i < end; ++i) {
        for_springs_of(i, [&](long s, double sign) {
          stiffness_times_v_.col(i) += sign * per_spring_.col(s);
          diagonal.col(i) += Vec2(blocks_[std::size_t(s)].xx, blocks_[std::size_t(s)].yy);
        });
      }
    });
  } else {
    for (long i = 0; i < springs; ++i) {
      const Spring& s = model.springs[std::size_t(i)];
      const Vec2 pull = linearise_spring(i);
      const Block& block = blocks_[std::size_t(i)];
      stiffness_times_v_.col(s.p) += pull;
      stiffness_times_v_.col(s.q) -= pull;
      diagonal.col(s.p) += Vec2(block.xx, block.yy);
      diagonal.col(s.q) += Vec2(block.xx, block.yy);
    }
  }
  inverse_diagonal_ = diagonal.cwiseInverse();
  for (const int i : pinned_)
    inverse_diagonal_.col(i).setZero();
}

void ImplicitEuler::multiply(const Model& model, const Vectors& x, Vectors& product) const {
  // S (x_p − x_q) of spring s: added to p, taken from q.
  const auto term = [&](long s) {
    const Block& b = blocks_[std::size_t(s)];
    const double dx = x(0, b.p) - x(0, b.q), dy = x(1, b.p) - x(1, b.q);
    return Vec2(b.xx * dx + b.xy * dy, b.xy * dx + b.yy * dy);
  };
  const long n = long(x.cols());
  product.resize(2, n);
  if (splits(n)) {  // each spring's term once, then each particle gathers its springs'
    fill_per_spring(long(model.springs.size()), term);
    for_blocks(n, [&](long begin, long end) {
      for (long i = begin; i < end; ++i) {
        Vec2 sum = x.col(i) * model.mass[i];
        for_springs_of(i, [&](long s, double sign) { sum += sign * per_spring_.col(s); });
        product.col(i) = model.pinned[std::size_t(i)] ? Vec2::Zero() : sum;
      }
    });
    return;
  }
  product.noalias() = x * model.mass.asDiagonal();
  for (std::size_t i = 0; i < model.springs.size(); ++i) {
    const Block& b = blocks_[i];
    const double dx = x(0, b.p) - x(0, b.q), dy = x(1, b.p) - x(1, b.q);
    const double fx = b.xx * dx + b.xy * dy, fy = b.xy * dx + b.yy * dy;  // as term(i)
    product(0, b.p) += fx;
    product(1, b.p) += fy;
    product(0, b.q) -= fx;
    product(1, b.q) -= fy;
  }
  for (const int i : pinned_)
    product.col(i).setZero();
}

// The position of entry (row, col) in matrix_'s values: found once, when the pattern is built.
Eigen::Index ImplicitEuler::slot(int row, int col) const {
  const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
  const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
  return std::lower_bound(begin, end, row) - matrix_.innerIndexPtr();
}

void ImplicitEuler::build_pattern(const Model& model) {
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
  pattern_built_ = true;
}

// A x = b by a sparse LDLᵀ factorisation of A assembled at r_n (b and x: one column a particle).
Vectors ImplicitEuler::solve_directly(const Model& model, const Vectors& r, double h,
                                      const Vectors& b) {
  // The factorisation is the run's largest allocation by far, and the up-front guard does not
  // count it (most runs never need it): it is checked now, before anything of it is built.
  if (!analysed_) {
    const MemoryLimit limit = available_memory();
    if (const double needed = factorisation_bytes(double(free_.size())); needed > limit.bytes)
      throw InvalidParameter(
          "free particles", std::to_string(free_.size()),
          "implicit-euler's conjugate gradients did not converge in 100 iterations, and the "
          "direct solver that takes over would need " +
              mebibytes_text(needed) + "; " + mebibytes_text(limit.bytes) + " are free (" +
              limit.source +
              "): make h smaller (the step's matrix is then closer to M and conjugate gradients "
              "converge) or the grid smaller");
  }
  if (!pattern_built_) build_pattern(model);
  Eigen::Map<Eigen::VectorXd> values(matrix_.valuePtr(), matrix_.nonZeros());
  values = mass_values_ + h * damping_values_;
  for (std::size_t n = 0; n < model.springs.size(); ++n) {
    const Spring& s = model.springs[n];
    const Eigen::Matrix2d block =
        stiffness_block(r.col(s.p) - r.col(s.q), s.k, s.rest_length, /*clamp_compressed=*/true);
    const std::array<Eigen::Index, 16>& where = slots_[n];
    for (std::size_t k = 0; k < 4; ++k) {
      const double sign = k < 2 ? h * h : -h * h;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          if (const Eigen::Index at = where[4 * k + std::size_t(2 * i + j)]; at >= 0)
            values[at] += sign * block(i, j);
    }
  }
  if (!analysed_) direct_.analyzePattern(matrix_), analysed_ = true;
  direct_.factorize(matrix_);
  ++factorisations_;
  if (direct_.info() != Eigen::Success)
    throw StepFailed("the implicit step's matrix M + hC + h^2 K could not be factorised");
  Eigen::VectorXd free_b(2 * free_.size());
  for (int j = 0; j < free_.size(); ++j)
    free_b.segment<2>(2 * j) = b.col(free_.particle[std::size_t(j)]);
  const Eigen::VectorXd free_x = direct_.solve(free_b);
  Vectors x = Vectors::Zero(2, b.cols());
  for (int j = 0; j < free_.size(); ++j)
    x.col(free_.particle[std::size_t(j)]) = free_x.segment<2>(2 * j);
  return x;
}

void ImplicitEuler::step(const Model& model, double h, Vectors& r, Vectors& v) {
  if (fingerprint_.changed(model)) prepare(model);
  if (free_.size() == 0) return;
  const Vectors& a = model.acceleration(r, v);
  linearise(model, r, v, h);
  const long n = long(r.cols());
  rhs_.resize(2, n);
  // h f_n − h² K v_n, and its norm.
  const double scale = std::sqrt(sum_blocks(n, [&](long begin, long end) {
    const long count = end - begin;
    rhs_.middleCols(begin, count) =
        h * (a.middleCols(begin, count) * model.mass.segment(begin, count).asDiagonal());
    flat(rhs_, begin, end) -= h * h * flat(stiffness_times_v_, begin, end);
    for (long i = begin; i < end; ++i)
      if (model.pinned[std::size_t(i)]) rhs_.col(i).setZero();
    return flat(rhs_, begin, end).squaredNorm();
  }));
  // Solved for Δv / |rhs|, so that CG's tolerance is relative to a right-hand side of norm 1:
  // CG judges convergence by squared norms, which underflow once a decaying motion reaches
  // 1e-155 and would stop it before its first iteration.
  const bool know_last = guess_.cols() == n;  // the last step's Δv
  const bool know_two = know_last && previous_.cols() == n;
  if (scale == 0.0) {
    solution_.setZero(2, n);
  } else {
    // The first guess: Δv extrapolated from the last two steps (it changes smoothly from step to
    // step), which saves about one CG iteration of six over the last Δv alone.
    solution_.resize(2, n);
    for_blocks(n, [&](long begin, long end) {
      flat(rhs_, begin, end) /= scale;
      auto guess = flat(solution_, begin, end);
      if (know_two) {
        guess = (2.0 * flat(guess_, begin, end) - flat(previous_, begin, end)) / scale;
      } else if (know_last) {
        guess = flat(guess_, begin, end) / scale;
      } else {
        guess.setZero();
      }
    });
    const auto product = [&](const Vectors& x, Vectors& ax) { multiply(model, x, ax); };
    if (!conjugate_gradients(product, inverse_diagonal_, rhs_, solution_, implicit_euler_tolerance,
                             100, cg_))
      solution_ = solve_directly(model, r, h, rhs_);
  }
  if (know_last) {
    previous_.swap(guess_);
  } else {
    previous_.resize(2, 0);
  }
  guess_.resize(2, n);
  for_blocks(n, [&](long begin, long end) {
    flat(guess_, begin, end) = flat(solution_, begin, end) * scale;  // Δv
    for (long i = begin; i < end; ++i)
      if (!model.pinned[std::size_t(i)]) {
        v.col(i) += guess_.col(i);
        r.col(i) += h * v.col(i);
      }
  });
}

}  // namespace

std::unique_ptr<Integrator> make_implicit_euler() {
  return std::make_unique<ImplicitEuler>();
}

}  // namespace springlab::detail
