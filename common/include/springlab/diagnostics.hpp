// What the runner, the viewer and the tests measure of a state: energies and momenta.
#pragma once

#include "springlab/types.hpp"

#include <string>
#include <vector>

namespace springlab {

/// Σ ½ m_i |v_i|², J.
double kinetic_energy(const Eigen::VectorXd& mass, const Vectors& v);

/// Σ over springs of ½ k (|r_p - r_q| - ℓ0)², J. Its negative gradient is the spring force (1.1).
double spring_energy(const std::vector<Spring>& springs, const Vectors& r);

/// P = Σ m_i v_i, kg·m/s. Internal forces that obey F_qp = -F_pq leave it unchanged.
Vec2 linear_momentum(const Eigen::VectorXd& mass, const Vectors& v);

/// L = Σ m_i (r_i - about) × v_i (the z-component), kg·m²/s.
double angular_momentum(const Eigen::VectorXd& mass, const Vectors& r, const Vectors& v,
                        const Vec2& about = Vec2::Zero());

/// Σ m_i r_i / Σ m_i, m.
Vec2 centre_of_mass(const Eigen::VectorXd& mass, const Vectors& r);

/// -Σ m_i g·(r_i - start_i), J: gravity's potential energy, zero at the start positions.
double gravitational_energy(const Eigen::VectorXd& mass, const Vectors& r, const Vectors& start,
                            const Vec2& g);

struct Diagnostics {
  double kinetic = 0.0;           ///< J
  double potential = 0.0;         ///< spring energy, J
  double gravitational = 0.0;     ///< gravity's potential energy, zero at the start, J
  Vec2 momentum{0.0, 0.0};        ///< kg·m/s
  double angular_momentum = 0.0;  ///< about the origin, kg·m²/s
  /// Kinetic + spring + gravitational: constant without dampers, wind and pushes.
  double total() const { return kinetic + potential + gravitational; }
  /// Spring + gravitational: what the viewer's energy plot calls "potential", J.
  double all_potential() const { return potential + gravitational; }
};

/// "kinetic K, potential P" as the runner's and the viewer's summaries print it, J, with the
/// potential named and summed as the viewer's plot does (springs and gravity together); with
/// gravity on, "potential P (springs S, gravity G)".
std::string energy_parts(const Diagnostics& d, bool gravity);

Diagnostics diagnose(const Particles& particles, const std::vector<Spring>& springs);

/// The same with gravity g, its potential energy measured from the positions `start`.
Diagnostics diagnose(const Particles& particles, const std::vector<Spring>& springs, const Vec2& g,
                     const Vectors& start);

/// The same two with the springs' energy (J) already summed, e.g. by the fast path
/// (grid_forces.hpp).
Diagnostics diagnose(const Particles& particles, double spring_energy);
Diagnostics diagnose(const Particles& particles, double spring_energy, const Vec2& g,
                     const Vectors& start);

}  // namespace springlab
