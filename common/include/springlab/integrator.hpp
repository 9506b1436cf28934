// The numerical methods, kept apart from the physical model (lecture: "separate implementation
// for the numerical method"): an integrator only sees r, v and the acceleration function.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/types.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace springlab {

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string_view name() const = 0;
  /// Advances r and v by one step h with the model a = acceleration(r, v).
  virtual void step(const AccelerationFunction& acceleration, double h, Vectors& r, Vectors& v) = 0;
  /// Forgets anything remembered from earlier steps. Call it when r or v are changed from
  /// outside (a reset, a dragged particle); a change of h or of the particle count restarts too.
  virtual void restart() {}
};

/// "explicit-euler" (task 1), "verlet" (task 4).
std::vector<std::string> integrator_names();

bool is_integrator_name(std::string_view name);

/// The integrator `name`, running the functions of `impl`. Throws InvalidParameter naming the
/// known integrators for an unknown name.
std::unique_ptr<Integrator> make_integrator(std::string_view name, const Implementation& impl);

}  // namespace springlab
