// Stability theory for a scene: the linearised equations of motion about a configuration and the
// step limits of the methods that follow from them (handout equations (1.6) and (4.5), and
// handout/integrators.md). Dense eigen-solves, meant for small scenes (exact_particles_max); the
// frequency bound works for any size.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/parameters.hpp"
#include "springlab/scene.hpp"
#include "springlab/types.hpp"

#include <Eigen/Core>
#include <complex>
#include <string>
#include <string_view>
#include <vector>

namespace springlab {

/// System eigenvalues this much smaller than the largest belong to rigid motions: a free
/// translation is a double zero eigenvalue, which rounding splits by about √ε·|λ_max|.
inline constexpr double rigid_tolerance = 1e-6;

/// M δr'' = -K δr - C δv about a configuration r, for the free (unpinned) degrees of freedom.
struct LinearModel {
  Eigen::MatrixXd stiffness;  ///< K = ∂²(spring energy)/∂r², N/m
  Eigen::MatrixXd damping;    ///< C (dampers act on relative velocity, plus drag), N·s/m
  Eigen::VectorXd mass;       ///< M's diagonal, kg (each free particle's mass twice: x and y)
  /// The share of C's diagonal that comes from external forces (the wind's drag c(w − v)),
  /// N·s/m, per coordinate; empty without. Implicit Euler and velocity Verlet treat the
  /// springs' dampers implicitly but external forces explicitly, so this share limits their
  /// step: h < 2m/c for a mode the drag alone damps.
  Eigen::VectorXd drag;
};

LinearModel linearise(const std::vector<Spring>& springs, const Vectors& r,
                      const Eigen::VectorXd& mass, const std::vector<bool>& pinned);

/// ω_max, the highest angular frequency of the undamped model (K φ = ω² M φ), rad/s.
double highest_frequency(const LinearModel& model);

/// A of the first-order system y' = A y with y = (δr, δv): A = [[0, I], [-M⁻¹K, -M⁻¹C]], 1/s.
Eigen::MatrixXd system_matrix(const LinearModel& model);

/// The eigenvalues of a general real matrix, balanced first (a diagonal similarity by powers of 2,
/// Parlett and Reinsch's: it changes no eigenvalue and no entry's digits). Eigen's EigenSolver
/// does not balance, and on a stiff, light scene (k/m = 1e15 beside the identity's 1) its
/// rounding turned damped modes into growing ones: critical steps of 4e-18 s instead of 5e-8.
Eigen::VectorXcd balanced_eigenvalues(Eigen::MatrixXd a);

/// The eigenvalues λ of system_matrix(model), 1/s.
Eigen::VectorXcd system_eigenvalues(const LinearModel& model);

/// The eigenvalues of system_matrix(model) that deform the scene: rigid motions (|λ| at most
/// rigid_tolerance of the largest) left out, 1/s.
std::vector<std::complex<double>> deforming_eigenvalues(const LinearModel& model);

/// Explicit Euler's and RK4's step matrices are polynomials in hA, so their limit and growth
/// follow from the eigenvalues alone, and one eigen-solve serves both. `integrator` is
/// "explicit-euler" (|1 + hλ|) or "rk4" (|R(hλ)|, R(z) = 1 + z + z²/2 + z³/6 + z⁴/24).
/// The largest h stable on every λ, s:
double polynomial_critical_step(const std::vector<std::complex<double>>& lambda,
                                std::string_view integrator);
/// The largest growth factor per step at step h over the λ:
double polynomial_growth_factor(const std::vector<std::complex<double>>& lambda,
                                std::string_view integrator, double h);

/// Explicit Euler multiplies mode λ by 1 + hλ each step: the largest |1 + hλ| at step h over
/// the modes that deform the scene (λ ≠ 0; free translations stay as they are).
double explicit_euler_growth_factor(const LinearModel& model, double h);

/// The largest h with |1 + hλ| ≤ 1 for every λ ≠ 0: min over λ of -2 Re λ / |λ|², s. For one
/// damped spring it is 2ζ/ω = b/k (equation (1.6)); zero when some mode is undamped.
double explicit_euler_critical_step(const LinearModel& model);

/// 2/ω_max, the limit of Störmer–Verlet with a central-difference velocity (equation (4.5)), s.
double verlet_critical_step(const LinearModel& model);

/// c_max, the largest damping rate of the model: the largest eigenvalue of M^-½ C M^-½, 1/s.
double fastest_damping_rate(const LinearModel& model);

/// Task 4's Verlet finds v_n by iterating (4.1)-(4.2); each estimate shrinks the error by h c/2
/// (c a mode's damping rate), so it settles to 1e-12 within verlet_max_iterations only while
/// h c_max / 2 < 1e-12^(1/verlet_max_iterations) (0.76): the step limit of damping, s. Infinity
/// without damping.
double verlet_iteration_limit(const LinearModel& model);

/// Adds the wind's drag c(w − v) to the model: c on every free coordinate, as a damper to the
/// air (the gusts w(t) drive the motion but do not change its stability), and recorded in
/// model.drag as taken explicitly.
void add_drag(LinearModel& model, double drag);

/// An upper bound of ω_max without an eigen-solve, for a scene of any size, rad/s. Every
/// eigenvalue ω² of M⁻¹K lies in a Gershgorin disc of its rows, so ω_max² ≤ max_i Σ_j |K_ij| / m_i
/// over the free coordinates: one pass over the springs. Exact for one spring, at most about a
/// third high on the lab grids.
double highest_frequency_bound(const std::vector<Spring>& springs, const Vectors& r,
                               const Eigen::VectorXd& mass, const std::vector<bool>& pinned);

/// The same kind of bound for the damping: every c of a mode is at most max_i Σ_j |C_ij| / m_i,
/// 1/s.
double damping_rate_bound(const std::vector<Spring>& springs, const Eigen::VectorXd& mass,
                          const std::vector<bool>& pinned);

/// The matrix by which one step of `integrator` multiplies a small deviation from the state the
/// model was linearised about, on the deformation modes: rigid translations (the null space of
/// K + C) are removed first, as they give an eigenvalue of exactly 1 that is not an instability.
/// The state is (δr_n, δv_n), for verlet (δr_n, δr_{n-1}).
Eigen::MatrixXd step_matrix(const LinearModel& model, std::string_view integrator, double h);

/// The spectral radius of step_matrix: the factor by which the worst small deviation grows (> 1)
/// or shrinks (< 1) per step.
double step_growth_factor(const LinearModel& model, std::string_view integrator, double h);

/// The largest h with step_growth_factor ≤ 1, found by bisection to a relative 1e-9, s:
/// exact for any damping. About 40 dense eigen-solves of step_matrix: small scenes only.
/// 0 when no h > 0 is stable, infinity for implicit-euler.
double critical_step_by_bisection(const LinearModel& model, std::string_view integrator);

/// How critical_step obtains its value for a method. lower_bound: a step that is certainly
/// stable, from the bound on ω_max without an eigen-solve (the exact limit is larger, up to
/// about a third on the lab grids: 2/ω_bound = 0.067 s against 2/ω_max = 0.084 s on the 20×20
/// fabric).
enum class LimitSource {
  exact_formula,
  bisection,
  modal_estimate,
  lower_bound,
  no_limit,
  not_computed
};

/// Free particles up to which critical_step uses bisection for symplectic-euler.
inline constexpr int bisection_particles_max = 25;
/// Particles up to which stability_report solves eigenproblems (dense, O(n³)).
inline constexpr int exact_particles_max = 200;

struct CriticalStep {
  double step = 0.0;  ///< h_c, s: 0 never stable, infinity never unstable
  LimitSource source = LimitSource::not_computed;
};

/// The critical step h_c of the integrator `name` (integrator.hpp) for this model, s:
///   explicit-euler, rk4  exact per mode from the system eigenvalues λ: their step matrices are
///                        polynomials in hA, so each mode is multiplied by 1 + hλ or R(hλ);
///   verlet               2/ω_max (exact for any damping), or verlet_iteration_limit when
///                        smaller (strong damping);
///   velocity-verlet      2/ω_max, exact for any damping of the springs; by bisection when
///                        model.drag (taken explicitly) is not zero;
///   symplectic-euler     by bisection up to bisection_particles_max free particles; beyond, per
///                        mode 4/(c + √(c² + 4ω²)) with the modal damping c = φᵀCφ (exact when
///                        the damping is proportional to the stiffness, close on the lab grids);
///   implicit-euler       infinity without drag; by bisection with it (the drag is explicit:
///                        about 2m/c).
///   xpbd                 no limit from the springs and dampers (converged, a substep is
///                        backward Euler on them); with drag, which it takes explicitly, an
///                        estimate: each substep below 2m/c, so h < xpbd_substeps · 2m/c.
///                        Its other limit is accuracy, not stability: few substeps of few
///                        iterations leave stiff springs stretched (handout/integrators.md).
CriticalStep critical_step_of(const LinearModel& model, std::string_view integrator,
                              int xpbd_substeps = XpbdParameters{}.substeps);

/// The critical step of `integrator` estimated from bounds alone, for scenes too large for
/// eigen-solves: ω_max ≤ frequency_bound (rad/s) and every mode's damping rate c ≤ damping_bound
/// (1/s, drag included), and each per-mode limit falls as ω and c grow; drag_rate, the largest
/// c/m of an explicit drag (1/s), limits implicit Euler and velocity Verlet to 2/drag_rate. Not
/// computed for explicit-euler, whose limit hangs on each mode's damping ratio.
CriticalStep estimated_critical_step(std::string_view integrator, double frequency_bound,
                                     double damping_bound, double drag_rate = 0.0,
                                     int xpbd_substeps = XpbdParameters{}.substeps);

/// 1e-12^(1/verlet_max_iterations): the largest factor h c/2 by which each estimate of task 4's
/// Verlet iteration may shrink the error and still settle in time (0.76).
double verlet_iteration_factor();

/// critical_step_of(model, integrator).step.
double critical_step(const LinearModel& model, std::string_view integrator);

/// The model of a scene about its current configuration: its springs and dampers, and the
/// wind's drag when it blows. The drag c(w − v) is a damper to the air, c on every free degree
/// of freedom; the gusts w(t) drive the motion but do not change its stability.
LinearModel linearise(const Scene& scene);

/// Scene p at rest (no particle displaced), its springs built by impl.
Scene scene_at_rest(const SceneParameters& p, const Implementation& impl);

/// The model of scene p at rest (no displacement), its springs built by impl.
LinearModel linearise_at_rest(const SceneParameters& p, const Implementation& impl);

/// What `springlab-run --stability` prints for a scene, linearised at rest.
struct StabilityReport {
  int particles = 0;
  double frequency_bound = 0.0;  ///< rad/s, highest_frequency_bound
  bool exact = false;            ///< whether the scene was small enough for eigen-solves
  double frequency = 0.0;        ///< ω_max, rad/s, when exact
  struct Limit {
    std::string integrator;
    CriticalStep critical;  ///< when not exact: estimates from the bounds (see stability.cpp)
  };
  /// Every integrator, in integrator_names() order (when not exact, Verlet's 2/ω_bound is a
  /// lower_bound, as ω_max ≤ ω_bound).
  std::vector<Limit> limits;
};

/// Eigen-solves (exact limits) for scenes of up to `exact_particles` particles; beyond, estimates
/// from the bounds, one pass over the springs.
StabilityReport stability_report(const SceneParameters& p, const Implementation& impl,
                                 int exact_particles = exact_particles_max);

}  // namespace springlab
