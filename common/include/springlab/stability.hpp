// Stability theory for a scene: the linearised equations of motion about a configuration and the
// step limits of the methods that follow from them (handout equations (1.6) and (4.5)). Dense
// eigen-solves: meant for small scenes (up to a few hundred particles).
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <Eigen/Core>
#include <string_view>
#include <vector>

namespace springlab {

/// M δr'' = -K δr - C δv about a configuration r, for the free (unpinned) degrees of freedom.
struct LinearModel {
  Eigen::MatrixXd stiffness;  ///< K = ∂²(spring energy)/∂r², N/m
  Eigen::MatrixXd damping;    ///< C (dampers act on relative velocity), N·s/m
  Eigen::VectorXd mass;       ///< M's diagonal, kg (each free particle's mass twice: x and y)
};

LinearModel linearise(const std::vector<Spring>& springs, const Vectors& r,
                      const Eigen::VectorXd& mass, const std::vector<bool>& pinned);

/// ω_max, the highest angular frequency of the undamped model (K φ = ω² M φ), rad/s.
double highest_frequency(const LinearModel& model);

/// The eigenvalues λ of y' = A y with y = (δr, δv), A = [[0, I], [-M⁻¹K, -M⁻¹C]], 1/s.
Eigen::VectorXcd system_eigenvalues(const LinearModel& model);

/// Explicit Euler multiplies mode λ by 1 + hλ each step: the largest |1 + hλ| at step h over
/// the modes that deform the scene (λ ≠ 0; free translations stay as they are).
double explicit_euler_growth_factor(const LinearModel& model, double h);

/// The largest h with |1 + hλ| ≤ 1 for every λ ≠ 0: min over λ of -2 Re λ / |λ|², s. For one
/// damped spring it is 2ζ/ω = b/k (equation (1.6)); zero when some mode is undamped.
double explicit_euler_critical_step(const LinearModel& model);

/// 2/ω_max, the limit of Störmer–Verlet with a central-difference velocity (equation (4.5)), s.
double verlet_critical_step(const LinearModel& model);

/// The critical step of the integrator `name` (integrator.hpp) for this model, s.
double critical_step(const LinearModel& model, std::string_view integrator);

/// The model of scene p at rest (no displacement), its springs built by impl.
LinearModel linearise_at_rest(const SceneParameters& p, const Implementation& impl);

}  // namespace springlab
