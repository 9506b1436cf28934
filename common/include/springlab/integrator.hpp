// The numerical methods, kept apart from the physical model (lecture: "separate implementation
// for the numerical method"). Explicit methods only call a(r, v); the implicit one also reads the
// springs, masses and pins to linearise the spring forces. Handout page: handout/integrators.md.
//
// The seven methods, chosen by name everywhere (runner, viewer, scene files). "Cost" counts calls
// of a(r, v) per step; ω is a mode's angular frequency, ζ its damping ratio, ω_max the highest.
//
//   explicit-euler    r += h v_n, v += h a_n (the student's task 1 code). Order 1. Cost 1.
//                     Stable per mode for h < 2ζ/ω; never when a mode is undamped.
//   symplectic-euler  v += h a(r_n, v_n), then r += h v_{n+1}. Order 1. Cost 1.
//                     Stable per mode for h < 2(√(1+ζ²) − ζ)/ω = 4/(c + √(c² + 4ω²)), c = 2ζω.
//   verlet            Störmer with central-difference velocity (the student's task 4 code).
//                     Order 2. Cost 2 without dampers, a few more with them (an iteration).
//                     Stable for h < 2/ω_max whatever the damping.
//   velocity-verlet   kick h/2, drift h, kick h/2 with the dampers implicit (trapezoidal).
//                     Order 2. Cost 1 (the end-of-step acceleration is reused) plus a few
//                     conjugate-gradient products. Stable for h < 2/ω_max whatever the damping.
//   rk4               classical Runge–Kutta. Order 4. Cost 4. Stable where |R(hλ)| ≤ 1 for every
//                     mode, R(z) = 1 + z + z²/2 + z³/6 + z⁴/24; undamped h < 2√2/ω_max.
//   implicit-euler    backward Euler linearised once per step (Baraff & Witkin 1998), solved by
//                     conjugate gradients (a sparse LDLᵀ when CG stalls on a stiff system).
//                     Order 1. Cost 1 plus the springs' Jacobian blocks and a few matrix-free CG
//                     iterations (about 10 evaluations' worth in all on fabrics from 10×10 to
//                     300×300, tests/benchmarks/README.md). No step limit on the springs (it
//                     damps, ≈ hω/2 a step).
//   xpbd              extended position-based dynamics (Macklin, Müller, Chentanez 2016) with
//                     small steps (Macklin et al. 2019): each spring a distance constraint of
//                     compliance 1/k, its damper the constraint's damping term (along the
//                     spring) plus a damping-only constraint across it; gravity, wind and push
//                     taken explicitly at the start of each substep. xpbd.substeps substeps of
//                     xpbd.iterations Gauss–Seidel passes. Order 1 in h/substeps. Cost: no
//                     a(r, v) call; substeps × iterations passes over the springs and substeps
//                     evaluations of the external forces. Converged (many iterations) it is
//                     backward Euler on the springs and dampers, so it has no step limit on them;
//                     only the wind's drag, explicit, limits a substep to 2m/c.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/types.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace springlab {

/// What an integrator may know of the model. `acceleration` is the whole physics (springs,
/// dampers, external forces, pins); the rest describes the springs so that an implicit method can
/// build their Jacobians. All references stay owned by the caller.
struct Model {
  const AccelerationFunction& acceleration;  ///< a(r, v), m/s²; zero for pinned particles
  const std::vector<Spring>& springs;        ///< every spring and damper inside `acceleration`
  const Eigen::VectorXd& mass;               ///< m_i, kg
  const std::vector<bool>& pinned;           ///< pinned particles never move
  /// The forces other than the springs and dampers (gravity, wind, push) divided by the mass,
  /// m/s², zero for pinned particles: what xpbd takes explicitly. Null: there are none.
  const AccelerationFunction* external = nullptr;
};

/// What a step does besides evaluating a(r, v), counted rather than timed, so that tests and the
/// trade-off study can judge a method's work on a busy machine: the implicit methods' solves.
struct SolverWork {
  long products = 0;        ///< products A x of a linear solve (each one pass over the springs)
  long factorisations = 0;  ///< sparse LDLᵀ factorisations (implicit Euler's fallback)
  long projections = 0;     ///< xpbd: constraint projections (one spring, one pass)
  long external = 0;        ///< xpbd: evaluations of the external forces (Model::external)
};

/// implicit-euler's conjugate gradients stop when |b − A x| < this × |b| (a direct solve after
/// 100 iterations without it).
inline constexpr double implicit_euler_tolerance = 1e-12;

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string_view name() const = 0;
  /// Advances r and v by one step h of the model.
  virtual void step(const Model& model, double h, Vectors& r, Vectors& v) = 0;
  /// Forgets anything remembered from earlier steps. Call it when r or v are changed from
  /// outside (a reset, a dragged particle); a change of h, of the particle count or of the
  /// springs' dampers, masses or pins is noticed by the integrators themselves.
  virtual void restart() {}
  /// The solver work of every step so far (zero for the explicit methods).
  virtual SolverWork solver_work() const { return {}; }
};

/// The seven methods above: the six of the lab from the least to the most work per step, then xpbd.
std::vector<std::string> integrator_names();

bool is_integrator_name(std::string_view name);

/// "one of explicit-euler, symplectic-euler, …": the allowed values, for error messages.
std::string integrator_choices();

/// The integrator `name`; explicit-euler and verlet run the functions of `impl`, xpbd takes its
/// substeps and iterations from `xpbd`. Throws InvalidParameter naming the known integrators for
/// an unknown name.
std::unique_ptr<Integrator> make_integrator(std::string_view name, const Implementation& impl,
                                            const XpbdParameters& xpbd = {});

}  // namespace springlab
