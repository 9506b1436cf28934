#include "springlab/integrator.hpp"

#include "springlab/errors.hpp"
#include "springlab/verlet_support.hpp"

#include <algorithm>
#include <cmath>

namespace springlab {
namespace {

class ExplicitEuler final : public Integrator {
 public:
  explicit ExplicitEuler(const Implementation& impl) : impl_(impl) {}
  std::string_view name() const override { return "explicit-euler"; }
  void step(const AccelerationFunction& a, double h, Vectors& r, Vectors& v) override {
    impl_.explicit_euler_step(a, h, r, v);
  }

 private:
  const Implementation& impl_;
};

// Verlet remembers r_{n-1}; that memory only means something for the same h and particle count.
class Verlet final : public Integrator {
 public:
  explicit Verlet(const Implementation& impl) : impl_(impl) {}
  std::string_view name() const override { return "verlet"; }
  void step(const AccelerationFunction& a, double h, Vectors& r, Vectors& v) override {
    if (h != h_ || history_.previous_position.cols() != r.cols()) restart();
    h_ = h;
    impl_.verlet_step(a, h, r, v, history_);
  }
  void restart() override { history_ = VerletHistory{}; }

 private:
  const Implementation& impl_;
  VerletHistory history_;
  double h_ = 0.0;
};

}  // namespace

std::vector<std::string> integrator_names() {
  return {"explicit-euler", "verlet"};
}

bool is_integrator_name(std::string_view name) {
  const auto names = integrator_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::unique_ptr<Integrator> make_integrator(std::string_view name, const Implementation& impl) {
  if (name == "explicit-euler") return std::make_unique<ExplicitEuler>(impl);
  if (name == "verlet") return std::make_unique<Verlet>(impl);
  throw InvalidParameter("integrator", "\"" + std::string(name) + "\"",
                         "one of explicit-euler, verlet");
}

bool velocity_settled(const Vectors& v_new, const Vectors& v_old, const Vectors& r, double h) {
  const double change = (v_new - v_old).lpNorm<Eigen::Infinity>();
  const double scale = std::max(v_new.lpNorm<Eigen::Infinity>(), r.lpNorm<Eigen::Infinity>() / h);
  return std::isfinite(scale) && change <= 1e-12 * scale;  // an overflow never counts as settled
}

}  // namespace springlab
