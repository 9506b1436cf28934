// The kit's explicit one-step methods: symplectic Euler and classical RK4 (see integrator.hpp).
#include "integrators.hpp"
#include "springlab/parallel.hpp"

namespace springlab::detail {
namespace {

// v_{n+1} = v_n + h a(r_n, v_n), r_{n+1} = r_n + h v_{n+1}. Order 1, one evaluation a step,
// stable per mode for h < 2(√(1+ζ²) − ζ)/ω. Drifting with the new velocity is what makes it
// symplectic: without dampers its energy error stays bounded instead of growing.
class SymplecticEuler final : public Integrator {
 public:
  std::string_view name() const override { return "symplectic-euler"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override {
    const Vectors& a = model.acceleration(r, v);
    // Element-wise, so split over threads on large scenes with the same result.
    for_blocks(r.cols(), [&](long begin, long end) {
      const long count = end - begin;
      v.middleCols(begin, count) += h * a.middleCols(begin, count);
      r.middleCols(begin, count) += h * v.middleCols(begin, count);
    });
  }
};

// Classical Runge–Kutta on y' = (v, a(r, v)). Order 4, four evaluations a step, stable where
// |1 + z + z²/2 + z³/6 + z⁴/24| ≤ 1 for z = hλ of every mode (undamped: h < 2√2/ω_max).
// Not symplectic: without dampers its energy slowly decays.
class RungeKutta4 final : public Integrator {
 public:
  std::string_view name() const override { return "rk4"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override {
    const auto& a = model.acceleration;
    // Each stage's position goes into stage_r_, storage kept between steps: an argument such
    // as r + 0.5 h v would be a new matrix, allocated and freed at every stage.
    k1v_ = a(r, v);
    k2r_ = v + 0.5 * h * k1v_;
    stage_r_ = r + 0.5 * h * v;
    k2v_ = a(stage_r_, k2r_);
    k3r_ = v + 0.5 * h * k2v_;
    stage_r_ = r + 0.5 * h * k2r_;
    k3v_ = a(stage_r_, k3r_);
    k4r_ = v + h * k3v_;
    stage_r_ = r + h * k3r_;
    k4v_ = a(stage_r_, k4r_);
    r += h / 6.0 * (v + 2.0 * k2r_ + 2.0 * k3r_ + k4r_);
    v += h / 6.0 * (k1v_ + 2.0 * k2v_ + 2.0 * k3v_ + k4v_);
  }

 private:
  // Stage slopes, kept between steps only to reuse their storage: k_i r is a velocity and
  // k_i v an acceleration (k1 r is v itself); stage_r_ is the position a stage is evaluated at.
  Vectors k1v_, k2r_, k2v_, k3r_, k3v_, k4r_, k4v_, stage_r_;
};

}  // namespace

std::unique_ptr<Integrator> make_symplectic_euler() {
  return std::make_unique<SymplecticEuler>();
}

std::unique_ptr<Integrator> make_rk4() {
  return std::make_unique<RungeKutta4>();
}

}  // namespace springlab::detail
