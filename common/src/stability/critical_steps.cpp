// The step limits of all six integrators (stability.hpp): step matrices of the linear model,
// bisection on their spectral radius, the per-mode formulas and the report of the runner.
#include "springlab/eigen_solvers.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"
#include "support/numbers.hpp"

#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <limits>

namespace springlab {
namespace {

using internal::infinity;

// K and C scaled by M^(-1/2) on both sides (unit masses), restricted to the complement of the
// null space of K + C: the translations, which neither springs nor dampers resist. That
// complement is invariant under both (they are symmetric), so the deformation modes keep their
// dynamics exactly.
struct Deformation {
  Eigen::MatrixXd k, c, drag;  // drag: the share of c that the external forces give
};

Deformation deformation_modes(const LinearModel& model) {
  const Eigen::VectorXd scale = model.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd k = scale.asDiagonal() * model.stiffness * scale.asDiagonal();
  const Eigen::MatrixXd c = scale.asDiagonal() * model.damping * scale.asDiagonal();
  const solvers::SymmetricEigen solver = solvers::symmetric_eigen(k + c);
  const Eigen::VectorXd& values = solver.eigenvalues();
  const double threshold = 1e-9 * std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (values[i] > threshold) kept.push_back(i);
  // Column by column: the name of "every row" differs between Eigen 3.4 and 5 (issue 36).
  Eigen::MatrixXd basis(values.size(), Eigen::Index(kept.size()));
  for (std::size_t j = 0; j < kept.size(); ++j)
    basis.col(Eigen::Index(j)) = solver.eigenvectors().col(kept[j]);
  Eigen::MatrixXd drag = Eigen::MatrixXd::Zero(k.rows(), k.cols());
  if (model.drag.size() == model.mass.size())
    drag.diagonal() = model.drag.cwiseProduct(scale.cwiseAbs2());
  return {basis.transpose() * k * basis, basis.transpose() * c * basis,
          basis.transpose() * drag * basis};
}

// One step of each method applied to (x, v) of x'' = -K x - C v (unit masses), as a matrix.
Eigen::MatrixXd step_matrix_of(const Deformation& d, std::string_view integrator, double h) {
  const Eigen::Index n = d.k.rows();
  const Eigen::MatrixXd id = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n) = id;
  a.bottomLeftCorner(n, n) = -d.k;
  a.bottomRightCorner(n, n) = -d.c;
  Eigen::MatrixXd s(2 * n, 2 * n);
  if (integrator == "explicit-euler") {
    s = Eigen::MatrixXd::Identity(2 * n, 2 * n) + h * a;
  } else if (integrator == "rk4") {
    const Eigen::MatrixXd z = h * a;
    const Eigen::MatrixXd id2 = Eigen::MatrixXd::Identity(2 * n, 2 * n);
    s = id2 + z * (id2 + z * (id2 / 2.0 + z * (id2 / 6.0 + z / 24.0)));
  } else if (integrator == "symplectic-euler") {  // v' = v + h a(x, v), x' = x + h v'
    const Eigen::MatrixXd kick = id - h * d.c;
    s << id - h * h * d.k, h * kick, -h * d.k, kick;
  } else if (integrator == "verlet") {  // (I + hC/2) x_{n+1} = (2I - h²K) x_n - (I - hC/2) x_{n-1}
    const Eigen::PartialPivLU<Eigen::MatrixXd> p(id + 0.5 * h * d.c);
    s << p.solve(2.0 * id - h * h * d.k), p.solve(-(id - 0.5 * h * d.c)), id,
        Eigen::MatrixXd::Zero(n, n);
  } else if (integrator == "velocity-verlet") {
    Eigen::MatrixXd half(n, 2 * n);  // v_{n+1/2}
    half << -0.5 * h * d.k, id - 0.5 * h * d.c;
    Eigen::MatrixXd x(n, 2 * n);  // r_{n+1}
    x << id, Eigen::MatrixXd::Zero(n, n);
    x += h * half;
    Eigen::MatrixXd predicted(n, 2 * n);  // v* = v_{n+1/2} + h/2 a_n, where the drag is taken
    predicted << -0.5 * h * d.k, -0.5 * h * d.c;
    predicted += half;
    // (I + h/2 (C - D)) v_{n+1} = v_{n+1/2} - h/2 K r_{n+1} - h/2 D v*: dampers implicit, drag not
    s << x, Eigen::PartialPivLU<Eigen::MatrixXd>(id + 0.5 * h * (d.c - d.drag))
                .solve(half - 0.5 * h * d.k * x - 0.5 * h * d.drag * predicted);
  } else if (integrator == "implicit-euler") {
    // (I + h(C - D) + h²K) v' = v - hK x - hD v, x' = x + h v': the drag D is explicit
    Eigen::MatrixXd rhs(n, 2 * n);
    rhs << -h * d.k, id - h * d.drag;
    const Eigen::MatrixXd v =
        Eigen::PartialPivLU<Eigen::MatrixXd>(id + h * (d.c - d.drag) + h * h * d.k).solve(rhs);
    Eigen::MatrixXd x(n, 2 * n);
    x << id, Eigen::MatrixXd::Zero(n, n);
    s << x + h * v, v;
  } else {
    throw InvalidParameter("integrator", "\"" + std::string(integrator) + "\"",
                           integrator_choices());
  }
  return s;
}

double spectral_radius(const Eigen::MatrixXd& s) {
  if (s.size() == 0) return 0.0;
  return balanced_eigenvalues(s).cwiseAbs().maxCoeff();
}

// RK4's growth factor |R(z)| per step on a mode with hλ = z.
double rk4_growth(std::complex<double> z) {
  return std::abs(1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0))));
}

// The largest t with |R(t·direction)| ≤ 1 on all of [0, t]: a scan (the region reaches
// |z| < 3.1) and a bisection of the first crossing.
double rk4_reach(std::complex<double> direction) {
  const auto growth = [&](double t) { return rk4_growth(t * direction); };
  constexpr double scan = 1.0 / 256;
  double t = 0.0;
  while (t < 4.0 && growth(t + scan) <= 1.0 + 1e-12)
    t += scan;
  if (t >= 4.0) return infinity;
  double lo = t, hi = t + scan;
  for (int i = 0; i < 60; ++i)
    (growth(0.5 * (lo + hi)) <= 1.0 + 1e-12 ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// Symplectic Euler per mode of x'' = -ω² x - c x': stable for h ≤ 4/(c + √(c² + 4ω²)) (the
// Jury conditions of its 2×2 step matrix; 2/ω undamped, 2/c for a mode with ω = 0).
double symplectic_euler_mode_limit(double w2, double c) {
  return 4.0 / (c + std::sqrt(c * c + 4.0 * w2));
}

// Per mode of the undamped problem, with each mode's own damping c = φᵀCφ.
double symplectic_euler_modal_estimate(const LinearModel& model) {
  const Eigen::VectorXd scale = model.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd k = scale.asDiagonal() * model.stiffness * scale.asDiagonal();
  const Eigen::MatrixXd c = scale.asDiagonal() * model.damping * scale.asDiagonal();
  const solvers::SymmetricEigen solver = solvers::symmetric_eigen(k);
  const Eigen::VectorXd damping =
      (solver.eigenvectors().transpose() * c * solver.eigenvectors()).diagonal();
  const double largest = std::max(solver.eigenvalues().maxCoeff(), damping.maxCoeff());
  double limit = infinity;
  for (Eigen::Index i = 0; i < damping.size(); ++i) {
    const double w2 = std::max(0.0, solver.eigenvalues()[i]);
    if (w2 + damping[i] > 1e-9 * largest)
      limit = std::min(limit, symplectic_euler_mode_limit(w2, damping[i]));
  }
  return limit;
}

int free_particles(const LinearModel& model) {
  return int(model.mass.size() / 2);
}

bool has_drag(const LinearModel& model) {
  return model.drag.size() > 0 && model.drag.maxCoeff() > 0.0;
}

// 2 m / c of the lightest particle: the limit of a motion that the drag alone damps, taken
// explicitly (|1 - h c/m| <= 1).
double drag_limit(const LinearModel& model) {
  return 2.0 / model.drag.cwiseQuotient(model.mass).maxCoeff();
}

}  // namespace

Eigen::MatrixXd step_matrix(const LinearModel& model, std::string_view integrator, double h) {
  return step_matrix_of(deformation_modes(model), integrator, h);
}

double step_growth_factor(const LinearModel& model, std::string_view integrator, double h) {
  return spectral_radius(step_matrix(model, integrator, h));
}

double critical_step_by_bisection(const LinearModel& model, std::string_view integrator) {
  if (integrator == "implicit-euler" && !has_drag(model)) return infinity;
  const Deformation modes = deformation_modes(model);
  const auto stable = [&](double h) {
    return spectral_radius(step_matrix_of(modes, integrator, h)) <= 1.0 + 1e-9;
  };
  // Bracket from 2/max(ω_max, c_max), the scale of every explicit method's limit (the springs'
  // or, when damping dominates, the dampers'), by doubling or halving.
  const double rate = std::max(highest_frequency(model), fastest_damping_rate(model));
  if (rate == 0.0) return infinity;  // nothing acts on a deformation
  double hi = 2.0 / rate;
  int doublings = 0;
  while (stable(hi))
    if (hi *= 2.0; ++doublings > 60) return infinity;
  double lo = hi / 2.0;
  int halvings = 0;
  while (!stable(lo))
    if (hi = lo, lo /= 2.0; ++halvings > 60) return 0.0;
  while (hi - lo > 1e-9 * lo)
    (stable(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

CriticalStep critical_step_of(const LinearModel& model, std::string_view integrator,
                              int xpbd_substeps) {
  if (!is_integrator_name(integrator))
    throw InvalidParameter("integrator", "\"" + std::string(integrator) + "\"",
                           integrator_choices());
  if (model.mass.size() == 0) return {infinity, LimitSource::no_limit};  // all pinned
  if (integrator == "explicit-euler")
    return {explicit_euler_critical_step(model), LimitSource::exact_formula};
  if (integrator == "verlet")
    return {std::min(verlet_critical_step(model), verlet_iteration_limit(model)),
            LimitSource::exact_formula};
  if (integrator == "rk4")
    return {polynomial_critical_step(deforming_eigenvalues(model), "rk4"),
            LimitSource::exact_formula};
  if (integrator == "velocity-verlet" || integrator == "implicit-euler") {
    // Only an explicit drag limits them beyond the springs' 2/ω_max (velocity Verlet).
    const double springs = integrator == "implicit-euler" ? infinity : verlet_critical_step(model);
    if (!has_drag(model))
      return {springs, std::isinf(springs) ? LimitSource::no_limit : LimitSource::exact_formula};
    if (free_particles(model) <= bisection_particles_max)
      return {critical_step_by_bisection(model, integrator), LimitSource::bisection};
    return {std::min(springs, drag_limit(model)), LimitSource::modal_estimate};
  }
  if (integrator == "xpbd") {
    // Backward Euler on the springs and dampers when converged: no limit from them. The
    // external forces are explicit; of them only the drag acts like a damper, limiting each
    // substep h/substeps to 2m/c (|1 − (h/substeps) c/m| ≤ 1 for a motion it alone damps).
    if (!has_drag(model)) return {infinity, LimitSource::no_limit};
    return {std::max(1, xpbd_substeps) * drag_limit(model), LimitSource::modal_estimate};
  }
  if (integrator == "symplectic-euler") {
    if (free_particles(model) <= bisection_particles_max)
      return {critical_step_by_bisection(model, integrator), LimitSource::bisection};
    return {symplectic_euler_modal_estimate(model), LimitSource::modal_estimate};
  }
  throw InvalidParameter("integrator", "\"" + std::string(integrator) + "\"", integrator_choices());
}

std::vector<std::complex<double>> deforming_eigenvalues(const LinearModel& model) {
  const Eigen::VectorXcd all = system_eigenvalues(model);
  std::vector<std::complex<double>> lambda;
  if (all.size() == 0) return lambda;
  const double largest = all.cwiseAbs().maxCoeff();
  for (const auto& l : all)
    if (std::abs(l) > rigid_tolerance * largest) lambda.push_back(l);
  return lambda;
}

double polynomial_critical_step(const std::vector<std::complex<double>>& lambda,
                                std::string_view integrator) {
  const bool rk4 = integrator == "rk4";
  double limit = infinity;
  for (const auto& l : lambda)  // equation (1.6) per mode, or RK4's reach along λ
    limit = std::min(limit, rk4 ? rk4_reach(l / std::abs(l)) / std::abs(l)
                                : std::max(0.0, -2.0 * l.real() / std::norm(l)));
  return limit;
}

double polynomial_growth_factor(const std::vector<std::complex<double>>& lambda,
                                std::string_view integrator, double h) {
  const bool rk4 = integrator == "rk4";
  double growth = 0.0;
  for (const auto& l : lambda)
    growth = std::max(growth, rk4 ? rk4_growth(h * l) : std::abs(1.0 + h * l));
  return growth;
}

CriticalStep estimated_critical_step(std::string_view integrator, double frequency_bound,
                                     double damping_bound, double drag_rate, int xpbd_substeps) {
  const double w = frequency_bound, c = damping_bound;
  const auto estimate = [](double h) { return CriticalStep{h, LimitSource::modal_estimate}; };
  // 2m/c of the drag, explicit in every method (|1 - h c/m| <= 1 for a motion it alone damps).
  const double drag = drag_rate > 0.0 ? 2.0 / drag_rate : infinity;
  if (integrator == "symplectic-euler") return estimate(symplectic_euler_mode_limit(w * w, c));
  if (integrator == "verlet") {
    // 2/ω_max with ω_max ≤ ω_bound: a step that is certainly stable, not the limit itself;
    // the iteration's limit 2q/c_max with c_max ≤ c likewise.
    return {std::min(2.0 / w, 2.0 * verlet_iteration_factor() / c), LimitSource::lower_bound};
  }
  if (integrator == "velocity-verlet") {
    if (drag < 2.0 / w) return estimate(drag);
    return {2.0 / w, LimitSource::lower_bound};
  }
  if (integrator == "rk4") return estimate(std::min(2.0 * std::sqrt(2.0) / w, rk4_reach(-1.0) / c));
  if (integrator == "implicit-euler")
    return std::isinf(drag) ? CriticalStep{infinity, LimitSource::no_limit} : estimate(drag);
  if (integrator == "xpbd")
    return std::isinf(drag) ? CriticalStep{infinity, LimitSource::no_limit}
                            : estimate(std::max(1, xpbd_substeps) * drag);
  return {};  // explicit-euler: its limit hangs on each mode's damping ratio
}

double critical_step(const LinearModel& model, std::string_view integrator) {
  return critical_step_of(model, integrator).step;
}

StabilityReport stability_report(const SceneParameters& p, const Implementation& impl,
                                 int exact_particles) {
  const Scene scene = scene_at_rest(p, impl);
  const Particles& particles = scene.particles;
  StabilityReport report;
  report.particles = particles.size();
  report.frequency_bound =
      highest_frequency_bound(scene.springs, particles.position, particles.mass, particles.pinned);
  report.exact = report.particles <= exact_particles;
  if (report.exact) {
    const LinearModel model = linearise(scene);
    report.frequency = highest_frequency(model);
    for (const std::string& name : integrator_names())
      report.limits.push_back({name, critical_step_of(model, name, p.xpbd.substeps)});
    return report;
  }
  // Too large for eigen-solves: lower estimates from the bounds.
  const double drag = p.wind.enabled ? p.wind.drag / particles.mass.minCoeff() : 0.0;
  const double c = damping_rate_bound(scene.springs, particles.mass, particles.pinned) + drag;
  for (const std::string& name : integrator_names())
    report.limits.push_back(
        {name, estimated_critical_step(name, report.frequency_bound, c, drag, p.xpbd.substeps)});
  return report;
}

}  // namespace springlab
