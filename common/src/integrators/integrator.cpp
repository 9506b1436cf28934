#include "springlab/integrator.hpp"

#include "integrators/integrators.hpp"
#include "springlab/errors.hpp"
#include "springlab/verlet_support.hpp"

#include <algorithm>
#include <cmath>

namespace springlab {
namespace {

// The student's task 1 step (integrator.hpp: order 1, one evaluation, h < 2ζ/ω).
class ExplicitEuler final : public Integrator {
 public:
  explicit ExplicitEuler(const Implementation& impl) : impl_(impl) {}
  std::string_view name() const override { return "explicit-euler"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override {
    impl_.explicit_euler_step(model.acceleration, h, r, v);
  }

 private:
  const Implementation& impl_;
};

// The student's task 4 step (order 2, h < 2/ω_max). It remembers r_{n-1}; that memory only means
// something for the same h and particle count.
class Verlet final : public Integrator {
 public:
  explicit Verlet(const Implementation& impl) : impl_(impl) {}
  std::string_view name() const override { return "verlet"; }
  void step(const Model& model, double h, Vectors& r, Vectors& v) override {
    if (h != h_ || history_.previous_position.cols() != r.cols()) restart();
    h_ = h;
    impl_.verlet_step(model.acceleration, h, r, v, history_);
  }
  void restart() override { history_ = VerletHistory{}; }

 private:
  const Implementation& impl_;
  VerletHistory history_;
  double h_ = 0.0;
};

}  // namespace

std::vector<std::string> integrator_names() {
  return {"explicit-euler",
          "symplectic-euler",
          "verlet",
          "velocity-verlet",
          "rk4",
          "implicit-euler",
          "xpbd"};
}

bool is_integrator_name(std::string_view name) {
  const auto names = integrator_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string integrator_choices() {
  std::string text = "one of ";
  for (const std::string& name : integrator_names())
    text += (text.size() > 7 ? ", " : "") + name;
  return text;
}

std::unique_ptr<Integrator> make_integrator(std::string_view name, const Implementation& impl,
                                            const XpbdParameters& xpbd) {
  if (name == "explicit-euler") return std::make_unique<ExplicitEuler>(impl);
  if (name == "symplectic-euler") return detail::make_symplectic_euler();
  if (name == "verlet") return std::make_unique<Verlet>(impl);
  if (name == "velocity-verlet") return detail::make_velocity_verlet();
  if (name == "rk4") return detail::make_rk4();
  if (name == "implicit-euler") return detail::make_implicit_euler();
  if (name == "xpbd") return detail::make_xpbd(xpbd);
  throw InvalidParameter("integrator", "\"" + std::string(name) + "\"", integrator_choices());
}

}  // namespace springlab
