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
// conjugate gradients with M's diagonal plus the dampers' as preconditioner solve it in a few
// products, each Σ_dampers b (x_p − x_q) computed from the springs directly (no matrix is stored:
// that reads a third of the memory a sparse C does, for x and y at once).
// (A sparse LDLᵀ factorisation, reused every step, cost 70 ms a step on a 300×300 fabric: its
// fill-in grows faster than the grid; CG's work grows with the number of springs.) a(r_{n+1},
// v_{n+1}) = a(r_{n+1}, v*) − M⁻¹Cδ is then known without another evaluation and starts the next
// step: one evaluation a step. Forces with a velocity dependence of their own (not the dampers) are
// taken at v*, an O(h²) change of a: the order stays 2.
#include "integrators/integrators.hpp"
#include "integrators/spring_matrices.hpp"
#include "springlab/errors.hpp"
#include "springlab/parallel.hpp"

namespace springlab::detail {
namespace {

class VelocityVerlet final : public Integrator {
 public:
  std::string_view name() const override { return "velocity-verlet"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override;
  void restart() override { known_acceleration_ = false; }
  SolverWork solver_work() const override { return {cg_.products, 0}; }

 private:
  // One damper as the product needs it: 16 bytes instead of the spring's 40.
  struct Damper {
    int p, q;  // its particles
    double b;  // N·s/m
  };

  void prepare(const Model& model, double h);
  bool state_is_last_steps(const Vectors& r, const Vectors& v) const;
  void damp(const Vectors& x, Vectors& damped) const;  // C x, zero at pinned particles

  ModelFingerprint fingerprint_;
  double h_ = 0.0;
  std::vector<int> pinned_;      // the pinned particles
  std::vector<Damper> dampers_;  // every spring's damper with b > 0
  Vectors inverse_diagonal_;     // 1 / diagonal of M + h/2 C, in x and y; 0 where pinned
  ConjugateGradientStorage cg_;
  bool known_acceleration_ = false;  // a_n below belongs to (r_end_, v_end_)
  Vectors acceleration_, predicted_, rhs_, correction_, damped_, r_end_, v_end_;
};

void VelocityVerlet::prepare(const Model& model, double h) {
  if (!fingerprint_.changed(model) && h == h_) return;
  h_ = h;
  known_acceleration_ = false;
  pinned_.clear();
  for (std::size_t i = 0; i < model.pinned.size(); ++i)
    if (model.pinned[i]) pinned_.push_back(int(i));
  dampers_.clear();
  Eigen::VectorXd diagonal = model.mass;
  for (const Spring& s : model.springs)
    if (s.b != 0.0) {
      dampers_.push_back({s.p, s.q, s.b});
      diagonal[s.p] += 0.5 * h * s.b;
      diagonal[s.q] += 0.5 * h * s.b;
    }
  inverse_diagonal_ = diagonal.cwiseInverse().transpose().replicate<2, 1>();
  for (const int i : pinned_)
    inverse_diagonal_.col(i).setZero();
}

void VelocityVerlet::damp(const Vectors& x, Vectors& damped) const {
  damped.setZero(2, x.cols());
  for (const Damper& d : dampers_) {
    const Vec2 f = d.b * (x.col(d.p) - x.col(d.q));
    damped.col(d.p) += f;
    damped.col(d.q) -= f;
  }
  for (const int i : pinned_)
    damped.col(i).setZero();
}

bool VelocityVerlet::state_is_last_steps(const Vectors& r, const Vectors& v) const {
  return known_acceleration_ && r.cols() == r_end_.cols() && r == r_end_ && v == v_end_;
}

void VelocityVerlet::step(const Model& model, double h, Vectors& r, Vectors& v) {
  prepare(model, h);
  if (!state_is_last_steps(r, v)) acceleration_ = model.acceleration(r, v);
  // Element-wise: split over threads on large scenes with the same result.
  for_blocks(long(r.cols()), [&](long begin, long end) {
    const long count = end - begin;
    const auto a = acceleration_.middleCols(begin, count);
    auto vb = v.middleCols(begin, count);
    vb += 0.5 * h * a;  // v_{n+1/2}
    r.middleCols(begin, count) += h * vb;
    vb += 0.5 * h * a;  // the predictor v*
  });
  predicted_ = model.acceleration(r, v);
  if (pinned_.size() < std::size_t(r.cols())) {
    // (M + h/2 C) δ = h/2 M (a(r_{n+1}, v*) − a_n), for x and y at once; δ = 0 where pinned.
    rhs_ = 0.5 * h * ((predicted_ - acceleration_) * model.mass.asDiagonal());
    for (const int i : pinned_)
      rhs_.col(i).setZero();
    const auto kick = [&](const Vectors& x, Vectors& product) {
      damp(x, product);
      product = 0.5 * h * product + x * model.mass.asDiagonal();
    };
    correction_.setZero(2, r.cols());
    if (!conjugate_gradients(kick, inverse_diagonal_, rhs_, correction_, 1e-13, 2 * int(r.cols()),
                             cg_))
      throw StepFailed("velocity-verlet: the damped half-kick (M + h/2 C) d = rhs did not solve");
    damp(correction_, damped_);  // C δ, N
    v += correction_;
    predicted_ -= damped_ * model.mass.cwiseInverse().asDiagonal();
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
