// Velocity Verlet with the dampers of the last half-kick treated implicitly (trapezoidal rule):
//   v_{n+1/2} = v_n + h/2 a(r_n, v_n),   r_{n+1} = r_n + h v_{n+1/2},
//   v_{n+1}   = v_{n+1/2} + h/2 a(r_{n+1}, v_{n+1}).
// Order 2 also with dampers (a lagged velocity in the last kick would make it order 1); stable for
// h < 2/ω_max whatever the damping (its positions obey the same recurrence as task 4's Verlet).
//
// The implicit kick is solved directly rather than by the fixed-point iteration of task 4: the
// dampers make a linear in v, a(r, v + δ) = a(r, v) − M⁻¹Cδ with a constant C, so after one
// evaluation at the explicit predictor v* = v_{n+1/2} + h/2 a_n the correction δ solves
//   (M + h/2 C) δ = h/2 M (a(r_{n+1}, v*) − a_n)
// exactly, for any damping (the iteration diverges once h·c/2 ≥ 1). M + h/2 C is symmetric
// positive definite, the same for x and y (dampers act alike on both) and close to M, so
// conjugate gradients with M's diagonal as preconditioner solve it in a few sparse products.
// (A sparse LDLᵀ factorisation, reused every step, cost 70 ms a step on a 300×300 fabric: its
// fill-in grows faster than the grid; CG's work grows with the number of springs.) a(r_{n+1},
// v_{n+1}) = a(r_{n+1}, v*) − M⁻¹Cδ is then known without another evaluation and starts the next
// step: one evaluation a step. Forces with a velocity dependence of their own (not the dampers) are
// taken at v*, an O(h²) change of a: the order stays 2.
#include "integrators.hpp"
#include "spring_matrices.hpp"
#include "springlab/errors.hpp"

#include <Eigen/IterativeLinearSolvers>

namespace springlab::detail {
namespace {

class VelocityVerlet final : public Integrator {
 public:
  std::string_view name() const override { return "velocity-verlet"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override;
  void restart() override { known_acceleration_ = false; }

 private:
  void prepare(const Model& model, double h);
  bool state_is_last_steps(const Vectors& r, const Vectors& v) const;

  ModelFingerprint fingerprint_;
  double h_ = 0.0;
  std::vector<int> free_;                    // the free particles
  Eigen::SparseMatrix<double> damping_;      // C of one coordinate, free particles
  Eigen::VectorXd free_mass_;                // their masses, kg
  Eigen::SparseMatrix<double> kick_matrix_;  // M + h/2 C
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> kick_;
  bool known_acceleration_ = false;  // a_n below belongs to (r_end_, v_end_)
  Vectors acceleration_, predicted_, r_end_, v_end_;
};

void VelocityVerlet::prepare(const Model& model, double h) {
  if (!fingerprint_.changed(model) && h == h_) return;
  h_ = h;
  known_acceleration_ = false;
  const FreeParticles free(model.pinned);
  free_ = free.particle;
  damping_ = scalar_damping(model.springs, free);
  free_mass_ = model.mass(free_);
  // M as a sparse matrix of its own: writing into kick.diagonal() would only reach entries that
  // exist, and a particle without dampers has none.
  const auto n = Eigen::Index(free_.size());
  Eigen::SparseMatrix<double> mass(n, n);
  mass.setIdentity();
  mass.diagonal() = free_mass_;
  kick_matrix_ = mass + 0.5 * h * damping_;
  kick_.setTolerance(1e-13);
  kick_.compute(kick_matrix_);
}

bool VelocityVerlet::state_is_last_steps(const Vectors& r, const Vectors& v) const {
  return known_acceleration_ && r.cols() == r_end_.cols() && r == r_end_ && v == v_end_;
}

void VelocityVerlet::step(const Model& model, double h, Vectors& r, Vectors& v) {
  prepare(model, h);
  if (!state_is_last_steps(r, v)) acceleration_ = model.acceleration(r, v);
  v += 0.5 * h * acceleration_;  // v_{n+1/2}
  r += h * v;
  v += 0.5 * h * acceleration_;  // the predictor v*
  predicted_ = model.acceleration(r, v);
  if (!free_.empty()) {
    Eigen::MatrixX2d rhs =
        (predicted_(Eigen::all, free_) - acceleration_(Eigen::all, free_)).transpose();
    rhs = 0.5 * h * free_mass_.asDiagonal() * rhs;
    const Eigen::MatrixX2d correction = kick_.solve(rhs);
    if (kick_.info() != Eigen::Success)
      throw StepFailed("velocity-verlet: the damped half-kick (M + h/2 C) d = rhs did not solve");
    const Eigen::MatrixX2d damped = damping_ * correction;  // C δ, N
    v(Eigen::all, free_) += correction.transpose();
    predicted_(Eigen::all, free_) -= (free_mass_.cwiseInverse().asDiagonal() * damped).transpose();
  }
  acceleration_ = predicted_;
  r_end_ = r;
  v_end_ = v;
  known_acceleration_ = true;
}

}  // namespace

std::unique_ptr<Integrator> make_velocity_verlet() {
  return std::make_unique<VelocityVerlet>();
}

}  // namespace springlab::detail
