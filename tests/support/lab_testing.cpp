#include "lab_testing.hpp"

#include "springlab/diagnostics.hpp"

#include <cmath>

namespace springlab::testing {

namespace {
// Catch2 prints doubles in fixed notation with 10 decimals, which shows the tolerances of these
// tests (1e-12) as 0; 15 decimals show them, and Catch drops the trailing zeros.
const bool precise_doubles = (Catch::StringMaker<double>::precision = 15, true);
}  // namespace

std::string IsNear::describe() const {
  std::ostringstream out;
  out.precision(12);
  out << "is within " << tolerance_ << " of " << Catch::Detail::stringify(expected_);
  return out.str();
}

double TwoMassExact::omega() const {
  return std::sqrt(2.0 * k / mass);
}
double TwoMassExact::zeta() const {
  return b / std::sqrt(2.0 * k * mass);
}

double TwoMassExact::stretch(double t) const {
  const double c = 2.0 * b / mass;
  const double wd = std::sqrt(omega() * omega() - c * c / 4.0);
  return std::exp(-c * t / 2.0) * (u0 * std::cos(wd * t) + c * u0 / (2.0 * wd) * std::sin(wd * t));
}

double TwoMassExact::stretch_rate(double t) const {
  // d/dt of stretch(): for u(0) = u0, u'(0) = 0 it is -(ω²/ω_d) u0 e^(-ct/2) sin(ω_d t).
  const double c = 2.0 * b / mass;
  const double wd = std::sqrt(omega() * omega() - c * c / 4.0);
  return -omega() * omega() / wd * u0 * std::exp(-c * t / 2.0) * std::sin(wd * t);
}

SceneParameters two_masses(double k, double b, double mass, double u0, double h,
                           const std::string& integrator) {
  SceneParameters p = task_scene(1);
  p.structural.k = k;
  p.structural.b = b;
  p.mass = mass;
  p.displaced = "1";
  p.displacement = Vec2(u0, 0.0);
  p.step = h;
  p.integrator = integrator;
  return p;
}

SceneParameters lab_grid(int rows, int cols, bool shear, double h, const std::string& integrator) {
  SceneParameters p;
  p.rows = rows;
  p.cols = cols;
  p.shear.enabled = shear;
  p.displacement = Vec2::Zero();
  p.step = h;
  p.integrator = integrator;
  return p;
}

SceneParameters fabric_10x10(double h, const std::string& integrator) {
  SceneParameters p = lab_grid(10, 10, true, h, integrator);
  p.name = "fabric 10x10";
  p.bend.enabled = true;  // the fabric's springs; its gravity, wind and pins only move the rest
  return p;
}

PerturbedRun perturbed_run(SceneParameters p, const Implementation& impl, double h,
                           const std::string& integrator, long steps, double ceiling) {
  p.step = h;
  p.integrator = integrator;
  Scene scene = perturbed_at_rest(p, impl, 1e-9, 5);
  PerturbedRun result;
  result.start = strain_norm(scene.springs, scene.particles.position);
  const std::vector<double> history =
      strain_history(std::move(scene), impl, steps, 0.0, ceiling * result.start);
  result.steps = long(history.size());
  result.largest = result.start;
  for (double norm : history)
    result.largest = std::max(result.largest, norm);
  result.last = history.empty() ? result.start : history.back();
  return result;
}

void run(Simulation& sim, long steps, const std::function<void(const Simulation&)>& observe) {
  for (long n = 0; n < steps; ++n) {
    sim.step();
    observe(sim);
  }
}

double largest_strain(const std::vector<Spring>& springs, const Vectors& r) {
  double largest = 0.0;
  for (const Spring& s : springs)
    largest = std::max(largest, std::abs((r.col(s.p) - r.col(s.q)).norm() - s.rest_length));
  return largest;
}

double growth_factor_from_peaks(const std::vector<double>& samples, double skip) {
  double sn = 0, sy = 0, snn = 0, sny = 0, count = 0;
  for (auto n = std::max<std::size_t>(1, std::size_t(skip * double(samples.size())));
       n + 1 < samples.size(); ++n) {
    const double a = std::abs(samples[n]);
    if (a > 0 && a >= std::abs(samples[n - 1]) && a > std::abs(samples[n + 1])) {
      const double x = double(n), y = std::log(a);
      sn += x, sy += y, snn += x * x, sny += x * y, count += 1;
    }
  }
  if (count < 3) return std::nan("");
  const double slope = (count * sny - sn * sy) / (count * snn - sn * sn);
  return std::exp(slope);
}

double observed_order(double error_h, double error_half_h) {
  return std::log2(error_h / error_half_h);
}

void randomise(Particles& particles, double spread, double speed, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < particles.size(); ++i) {
    particles.position.col(i) += spread * Vec2(unit(engine), unit(engine));
    particles.velocity.col(i) = speed * Vec2(unit(engine), unit(engine));
  }
}

Scene perturbed_at_rest(const SceneParameters& p, const Implementation& impl, double amplitude,
                        unsigned seed) {
  SceneParameters still = p;
  still.displacement = Vec2::Zero();
  Scene scene = build_scene(still, impl);
  randomise(scene.particles, amplitude, 0.0, seed);
  return scene;
}

double strain_norm(const std::vector<Spring>& springs, const Vectors& r) {
  double sum = 0.0;
  for (const Spring& s : springs)
    sum += std::pow((r.col(s.p) - r.col(s.q)).norm() - s.rest_length, 2);
  return std::sqrt(sum);
}

std::vector<double> strain_history(Scene scene, const Implementation& impl, long steps,
                                   double floor, double ceiling) {
  Simulation sim(std::move(scene), impl, no_divergence_stop());
  std::vector<double> history;
  history.reserve(std::size_t(steps));
  for (long n = 0; n < steps; ++n) {
    sim.step();
    const double norm = strain_norm(sim.scene().springs, sim.particles().position);
    if (!(norm >= floor && norm <= ceiling)) break;
    history.push_back(norm);
  }
  return history;
}

double measured_growth_factor(Scene scene, const Implementation& impl, long steps) {
  return growth_factor_from_peaks(strain_history(std::move(scene), impl, steps), 0.5);
}

Vectors energy_force(const std::vector<Spring>& springs, const Vectors& r, double d) {
  Vectors force(2, r.cols());
  for (Eigen::Index i = 0; i < r.cols(); ++i)
    for (int axis = 0; axis < 2; ++axis) {
      Vectors plus = r, minus = r;
      plus(axis, i) += d;
      minus(axis, i) -= d;
      force(axis, i) = -(spring_energy(springs, plus) - spring_energy(springs, minus)) / (2 * d);
    }
  return force;
}

bool carries(const Spring& spring, SpringFamily family, const SpringFamilyParameters& values) {
  return spring.family == family && spring.k == values.k && spring.b == values.b &&
         spring.rest_length == values.rest_length;
}

double momentum_drift(Simulation& sim, long steps) {
  const Vec2 start = sim.diagnostics().momentum;
  double worst = 0.0;
  run(sim, steps, [&](const Simulation& s) {
    worst = std::max(worst, (s.diagnostics().momentum - start).norm());
  });
  return worst;
}

}  // namespace springlab::testing
