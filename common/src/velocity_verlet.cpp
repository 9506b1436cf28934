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
// positive definite and constant while h and the springs stay: it is factorised once (sparse
// LDLᵀ, one coordinate, as dampers act alike on x and y) and each step costs one
// back-substitution. a(r_{n+1}, v_{n+1}) = a(r_{n+1}, v*) − M⁻¹Cδ is then known without another
// evaluation and starts the next step: one evaluation a step. Forces with a velocity dependence
// of their own (not the dampers) are taken at v*, an O(h²) change of a: the order stays 2.
#include "integrators.hpp"
#include "spring_matrices.hpp"

#include <Eigen/SparseCholesky>

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
  std::vector<int> free_;                                    // the free particles
  Eigen::SparseMatrix<double> damping_;                      // C of one coordinate, free particles
  Eigen::VectorXd free_mass_;                                // their masses, kg
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> kick_;  // M + h/2 C, factorised
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
  Eigen::SparseMatrix<double> kick = 0.5 * h * damping_;
  kick.diagonal() += free_mass_;
  kick_.compute(kick);
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
