// XPBD, extended position-based dynamics, with small steps (integrator.hpp; handout/integrators.md,
// "XPBD"). Written from the method's equations for the kit's spring–damper model:
//
// Each step h is cut into N = xpbd.substeps substeps of length s = h/N. A substep
//   1. kicks and drifts with the forces that are not springs: v += s a_ext(r, v), x = r + s v
//      (gravity, wind, push; pinned particles have none and do not move);
//   2. projects every spring's constraint C = |x_p − x_q| − ℓ0 with compliance α = 1/k, in
//      xpbd.iterations Gauss–Seidel passes over the springs, each moving p and q at once:
//        Δλ = (−C − α̃ λ − γ ∇C·(x − r)) / ((1 + γ)(w_p + w_q) + α̃),  α̃ = α/s², γ = α̃ β s,
//        x_p += w_p Δλ n,  x_q −= w_q Δλ n,  λ += Δλ,
//      n the unit vector from q to p, w = 1/m (0 when pinned), β = b the damper's coefficient,
//      λ summed over the passes of one substep. Multiplied through by k s², the same update reads
//        Δλ = (−k s² C − λ − b s n·(Δ_p − Δ_q)) / ((k s² + b s)(w_p + w_q) + 1),
//      Δ_i = x_i − r_i the move of particle i in this substep so far: finite for k = 0 (a damper
//      alone) and tending to −C/(w_p + w_q), a rigid rod, as k → ∞; its denominator is at least 1.
//      The kit's damper, F = −b (v_p − v_q), also acts across the spring, where the constraint's
//      gradient has no component: that part is a second, damping-only constraint along
//      t = (−n_y, n_x), the same update with k = 0:
//        Δμ = (−μ − b s t·(Δ_p − Δ_q)) / (b s (w_p + w_q) + 1),  x_p += w_p Δμ t,  x_q −= w_q Δμ t;
//   3. takes the velocity from the move: v = (x − r)/s, and r = x.
//
// Converged (λ and μ settled), λ n + μ t = s² (−k C n − b (x_p − r_p − x_q + r_q)/s): the spring
// and damper forces at the end of the substep, so the substep is backward Euler on the springs and
// dampers (not linearised) and symplectic Euler on the rest. Every projection moves p and q by
// opposite momenta (m_p w_p = m_q w_q = 1), so the springs never change the total momentum.
#include "integrators.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace springlab::detail {
namespace {

class Xpbd final : public Integrator {
 public:
  explicit Xpbd(const XpbdParameters& parameters) : parameters_(parameters) {}
  std::string_view name() const override { return "xpbd"; }
  SolverWork solver_work() const override { return work_; }

  void step(const Model& model, double h, Vectors& r, Vectors& v) override {
    const long n = r.cols();
    const int substeps = std::max(1, parameters_.substeps);
    const int iterations = std::max(1, parameters_.iterations);
    const double s = h / substeps;
    inverse_mass_.resize(n);
    for (long i = 0; i < n; ++i)
      inverse_mass_[i] = model.pinned[i] ? 0.0 : 1.0 / model.mass[i];
    const std::size_t springs = model.springs.size();
    lambda_.resize(springs);
    mu_.resize(springs);
    for (int substep = 0; substep < substeps; ++substep) {
      if (model.external) {
        v += s * (*model.external)(r, v);
        ++work_.external;
      }
      start_ = r;
      r += s * v;
      std::fill(lambda_.begin(), lambda_.end(), 0.0);
      std::fill(mu_.begin(), mu_.end(), 0.0);
      for (int pass = 0; pass < iterations; ++pass)
        project(model.springs, s, r);
      work_.projections += long(springs) * iterations;
      v = (r - start_) / s;
    }
  }

 private:
  // One Gauss–Seidel pass over the springs (the file's comment, step 2).
  void project(const std::vector<Spring>& springs, double s, Vectors& r) {
    double* x = r.data();
    const double* x0 = start_.data();
    const double* w = inverse_mass_.data();
    const double s2 = s * s;
    for (std::size_t i = 0; i < springs.size(); ++i) {
      const Spring& spring = springs[i];
      const long p = 2L * spring.p, q = 2L * spring.q;
      const double wp = w[spring.p], wq = w[spring.q], sum = wp + wq;
      const double dx = x[p] - x[q], dy = x[p + 1] - x[q + 1];
      const double length_squared = dx * dx + dy * dy;
      if (sum == 0.0 || length_squared == 0.0) continue;  // both pinned, or no direction
      const double length = std::sqrt(length_squared);
      const double nx = dx / length, ny = dy / length;
      // Δ_p − Δ_q, the ends' relative move in this substep so far.
      const double mx = (x[p] - x0[p]) - (x[q] - x0[q]);
      const double my = (x[p + 1] - x0[p + 1]) - (x[q + 1] - x0[q + 1]);
      const double ks2 = spring.k * s2, bs = spring.b * s;
      const double along =
          (-ks2 * (length - spring.rest_length) - lambda_[i] - bs * (nx * mx + ny * my)) /
          ((ks2 + bs) * sum + 1.0);
      lambda_[i] += along;
      double across = 0.0;
      if (bs > 0.0) {
        across = (-mu_[i] - bs * (nx * my - ny * mx)) / (bs * sum + 1.0);
        mu_[i] += across;
      }
      const double cx = along * nx - across * ny, cy = along * ny + across * nx;
      x[p] += wp * cx;
      x[p + 1] += wp * cy;
      x[q] -= wq * cx;
      x[q + 1] -= wq * cy;
    }
  }

  XpbdParameters parameters_;
  SolverWork work_;
  Eigen::VectorXd inverse_mass_;  // w_i = 1/m_i, 0 for pinned particles
  std::vector<double> lambda_;    // λ of each spring's distance constraint in this substep, kg·m
  std::vector<double> mu_;        // μ of each damper's sideways constraint, kg·m
  Vectors start_;                 // r at the substep's start, m
};

}  // namespace

std::unique_ptr<Integrator> make_xpbd(const XpbdParameters& parameters) {
  return std::make_unique<Xpbd>(parameters);
}

}  // namespace springlab::detail
