// The kit's explicit one-step methods: symplectic Euler and classical RK4 (see integrator.hpp).
#include "integrators/integrators.hpp"
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
    for_blocks(long(r.cols()), [&](long begin, long end) {
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
    const long n = long(r.cols());
    for (Vectors* storage : {&k1v_, &k2r_, &k2v_, &k3r_, &k3v_, &k4r_, &k4v_, &stage_r_})
      storage->resize(2, n);  // before any thread writes its block
    // Each stage's position goes into stage_r_, storage kept between steps: an argument such
    // as r + 0.5 h v would be a new matrix, allocated and freed at every stage. Every update is
    // element-wise, so it is split over threads on large scenes with the same result.
    const auto cols = [](auto& m, long begin, long end) {
      return m.middleCols(begin, end - begin);
    };
    const Vectors& a1 = a(r, v);
    for_blocks(n, [&](long b, long e) {
      cols(k1v_, b, e) = cols(a1, b, e);
      cols(k2r_, b, e) = cols(v, b, e) + 0.5 * h * cols(k1v_, b, e);
      cols(stage_r_, b, e) = cols(r, b, e) + 0.5 * h * cols(v, b, e);
    });
    const Vectors& a2 = a(stage_r_, k2r_);
    for_blocks(n, [&](long b, long e) {
      cols(k2v_, b, e) = cols(a2, b, e);
      cols(k3r_, b, e) = cols(v, b, e) + 0.5 * h * cols(k2v_, b, e);
      cols(stage_r_, b, e) = cols(r, b, e) + 0.5 * h * cols(k2r_, b, e);
    });
    const Vectors& a3 = a(stage_r_, k3r_);
    for_blocks(n, [&](long b, long e) {
      cols(k3v_, b, e) = cols(a3, b, e);
      cols(k4r_, b, e) = cols(v, b, e) + h * cols(k3v_, b, e);
      cols(stage_r_, b, e) = cols(r, b, e) + h * cols(k3r_, b, e);
    });
    const Vectors& a4 = a(stage_r_, k4r_);
    for_blocks(n, [&](long b, long e) {
      cols(k4v_, b, e) = cols(a4, b, e);
      cols(r, b, e) +=
          h / 6.0 *
          (cols(v, b, e) + 2.0 * cols(k2r_, b, e) + 2.0 * cols(k3r_, b, e) + cols(k4r_, b, e));
      cols(v, b, e) +=
          h / 6.0 *
          (cols(k1v_, b, e) + 2.0 * cols(k2v_, b, e) + 2.0 * cols(k3v_, b, e) + cols(k4v_, b, e));
    });
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
