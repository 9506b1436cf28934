// What the reference tests share: printing and comparing Eigen values in Catch2, the exact
// two-mass solution, and the measurements (growth factor, convergence order, symmetry) that turn
// a simulated run into a number theory predicts. Independent of the implementation under test.
#pragma once

#include "lab_catch.hpp"
#include "springlab/errors.hpp"
#include "springlab/scene.hpp"
#include "springlab/simulation.hpp"
#include "springlab/stability.hpp"
#include "springlab/types.hpp"

#include <cstdlib>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace Catch {
template <>
struct StringMaker<springlab::Vec2> {
  static std::string convert(const springlab::Vec2& v) {
    std::ostringstream out;
    out.precision(12);
    out << "(" << v.x() << ", " << v.y() << ")";
    return out.str();
  }
};
}  // namespace Catch

namespace springlab::testing {

/// Sets (or, with nullptr, removes) an environment variable of this process, on POSIX systems and
/// Windows alike (Windows has no setenv: an empty value removes it there).
inline void set_environment(const char* name, const char* value) {
#if defined(_WIN32)
  _putenv_s(name, value ? value : "");
#else
  if (value)
    setenv(name, value, 1);
  else
    unsetenv(name);
#endif
}

/// The lab's values (SceneParameters' defaults: h = 0.01 s, m = 0.2 kg, k = 20 N/m, ...).
inline const SceneParameters lab_values;

/// The stretch |r_1 - r_0| - l0 of the scene's first spring (the two-mass scenes).
inline double stretch_of(const Simulation& s) {
  const Vectors& r = s.particles().position;
  return (r.col(1) - r.col(0)).norm() - s.scene().springs.front().rest_length;
}

/// A planted mistake for add_gravity: F_i += g, the mass left out of m_i g.
inline void gravity_without_mass(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  for (Eigen::Index i = 0; i < mass.size(); ++i)
    force.col(i) += g;
}

/// Matches a Vec2 within `tolerance` (Euclidean distance) of `expected`; prints both on failure.
class IsNear : public lab_catch::MatcherBase<Vec2> {
 public:
  IsNear(Vec2 expected, double tolerance) : expected_(std::move(expected)), tolerance_(tolerance) {}
  bool match(const Vec2& actual) const override {
    return (actual - expected_).norm() <= tolerance_;
  }
  std::string describe() const override;

 private:
  Vec2 expected_;
  double tolerance_;
};

/// Two equal masses on one spring, released from rest with stretch u0 along the spring. The
/// stretch u = L - ℓ0 obeys u'' = -(2k/m) u - (2b/m) u' (each mass feels the spring and the
/// relative velocity is u'), an underdamped oscillator with the closed-form solution below.
struct TwoMassExact {
  double k, b, mass, u0;
  double omega() const;                 ///< √(2k/m), rad/s
  double zeta() const;                  ///< b / √(2km)
  double stretch(double t) const;       ///< u(t), m
  double stretch_rate(double t) const;  ///< u'(t), m/s
};

/// The task 1 scene with custom values: masses at (0, 0) and (1 + u0, 0), at rest.
SceneParameters two_masses(double k, double b, double mass, double u0, double h,
                           const std::string& integrator);

/// The lab grid rows×cols (structural always, shear if asked), nothing displaced.
SceneParameters lab_grid(int rows, int cols, bool shear, double h, const std::string& integrator);

/// The 10×10 test fabric: the lab grid with the fabric's three spring families (structural,
/// shear, bend), nothing displaced, no gravity, wind or pins (they move the rest state, and the
/// stability tests perturb a rest state).
SceneParameters fabric_10x10(double h, const std::string& integrator);

/// A run with no divergence stop: tests of instability watch the growth themselves.
inline DivergenceLimits no_divergence_stop() {
  return {1e300, 1};
}

/// Steps `sim` n times, calling observe(sim) after every step.
void run(Simulation& sim, long steps, const std::function<void(const Simulation&)>& observe);

/// The largest |L - ℓ0| over the springs, m: an amplitude that rigid motions do not change.
double largest_strain(const std::vector<Spring>& springs, const Vectors& r);

/// Per-step growth factor ρ of an oscillation from its samples, by a least-squares fit of
/// ln|peak| against step index over the local maxima of |samples| (the envelope grows as ρⁿ),
/// leaving out the first `skip` fraction of the samples (where other modes still show).
double growth_factor_from_peaks(const std::vector<double>& samples, double skip = 0.0);

/// The scene of p at rest, each particle then moved randomly by up to `amplitude` m: a small
/// start that excites every mode and keeps the motion in the linear range.
Scene perturbed_at_rest(const SceneParameters& p, const Implementation& impl, double amplitude,
                        unsigned seed);

/// sqrt(Σ (L - ℓ0)²) over the springs, m: how far the scene is deformed, blind to rigid motion.
double strain_norm(const std::vector<Spring>& springs, const Vectors& r);

/// The strain norm after every step of a run of `scene` with no divergence stop, up to `steps`
/// steps, ending early once it leaves [floor, ceiling] (rounding below, nonlinearity above).
std::vector<double> strain_history(Scene scene, const Implementation& impl, long steps,
                                   double floor = 1e-13, double ceiling = 1e-3);

/// The per-step growth factor of the fastest-growing (or slowest-decaying) mode that deforms
/// the scene: growth_factor_from_peaks over the second half of strain_history.
double measured_growth_factor(Scene scene, const Implementation& impl, long steps);

/// How a run from a tiny random deformation went (see perturbed_run).
struct PerturbedRun {
  double start = 0.0;    ///< strain norm at t = 0, m
  double largest = 0.0;  ///< the largest strain norm over the run, m
  double last = 0.0;     ///< the strain norm after the last step run, m
  long steps = 0;        ///< steps run: fewer than asked when the strain grew past the ceiling
};

/// Runs the scene of p (at rest, every particle moved randomly by up to 1e-9 m, so that every
/// mode is excited and the motion stays linear) at step h with `integrator` for up to `steps`
/// steps, stopping once the strain norm exceeds `ceiling` times its start.
PerturbedRun perturbed_run(SceneParameters p, const Implementation& impl, double h,
                           const std::string& integrator, long steps, double ceiling = 1e3);

/// Observed order p from errors e1 at step h and e2 at step h/2: log2(e1/e2).
double observed_order(double error_h, double error_half_h);

/// Positions near the grid of `scene` (each moved by up to `spread` m in x and y) and random
/// velocities up to `speed` m/s, from a fixed seed.
void randomise(Particles& particles, double spread, double speed, unsigned seed);

/// -dE/dr_i for every particle by central differences of spring_energy (step d, m): the force
/// the springs must exert, by the definition of a potential, N.
Vectors energy_force(const std::vector<Spring>& springs, const Vectors& r, double d = 1e-6);

/// True when the spring has this family and exactly the family's k, b and rest length.
bool carries(const Spring& spring, SpringFamily family, const SpringFamilyParameters& values);

/// The largest |P(t) - P(0)| of total linear momentum while stepping sim `steps` times, kg·m/s.
double momentum_drift(Simulation& sim, long steps);

/// The message of the InvalidParameter that `action` throws, or "" when it throws none.
template <class Action>
std::string rejection(Action&& action) {
  try {
    action();
  } catch (const InvalidParameter& error) {
    return error.what();
  }
  return "";
}

/// The index of grid particle [row, col].
inline int at(int row, int col, int cols) {
  return row * cols + col;
}

}  // namespace springlab::testing
