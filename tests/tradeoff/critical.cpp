// Critical steps: theory from stability.hpp, and measured by bisection on the step.
//
// Theory linearises each scene about an equilibrium: two masses and the grid at rest, the fabric
// where it hangs (gravity stretches it; hanging_equilibrium below). The measurement runs the
// linearised motion: the scene starts at that equilibrium with every particle moved randomly by
// 1e-6 m (every mode excited, the motion linear); a step counts as unstable when the largest
// change of a spring's length over the last tenth of the run exceeds that over the tenth before
// its middle, so the fastest-growing (or slowest-decaying) mode decides (a run that decays
// ten-thousandfold first is stable). Near its limit a method's growth per step is tiny (explicit
// Euler: about 2ζ²ε per step at ε beyond it), so the run length comes from the growth factor: long
// enough for growth just beyond the limit to reach e³.
//
// The fabric has 760 free coordinates: its system eigenvalues (a dense 1520×1520 nonsymmetric
// solve, 5–15 s here) are computed once and give explicit Euler's and RK4's limits and growth
// factors; --quick skips them and checks the Verlet methods only. Instead of a bisection from
// 0.5·h_c (16 runs of up to 400 particles) the runs test (1 ± 2 %)·h_c.
#include "measure.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <random>

namespace springlab::tradeoff {

namespace {

// The largest change of a spring's length from `length`, its length at the equilibrium (the
// hanging fabric's springs are stretched, up to 1.3 m: that strain does not oscillate).
double largest_strain(const std::vector<Spring>& springs, const Vectors& r,
                      const std::vector<double>& length) {
  double largest = 0.0;
  for (std::size_t i = 0; i < springs.size(); ++i)
    largest =
        std::max(largest, std::abs((r.col(springs[i].p) - r.col(springs[i].q)).norm() - length[i]));
  return largest;
}

std::vector<double> lengths(const Scene& scene) {
  std::vector<double> out;
  for (const Spring& s : scene.springs)
    out.push_back((scene.particles.position.col(s.p) - scene.particles.position.col(s.q)).norm());
  return out;
}

// Every free particle moved randomly by 1e-6 spacings: every mode excited, the motion linear.
Scene perturbed(Scene scene) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> offset(-1e-6, 1e-6);
  for (int i = 0; i < scene.particles.size(); ++i)
    if (!scene.particles.pinned[std::size_t(i)])
      scene.particles.position.col(i) +=
          Vec2(offset(random), offset(random)) * scene.parameters.spacing;
  return scene;
}

Scene at_rest(SceneParameters p) {
  p.displaced = "none";
  return build_scene(p, lab_implementation());
}

}  // namespace

// Where the fabric hangs: implicit Euler at a large step damps the fall (cheaply, 0.05 s of
// wall time), then Newton's method on the force balance F(r) = M a(r, 0) = 0 of the free
// particles, with K = -∂F/∂r the stiffness linearise() builds, converges in a few steps to
// rounding. The residual is the largest |a| left, m/s².
Equilibrium hanging_equilibrium(const SceneParameters& params) {
  SceneParameters p = params;
  p.displaced = "none";
  set_number(p, "step", 0.05);
  set_parameter(p, "integrator", "implicit-euler");
  Simulation relax(p, lab_implementation());
  relax.advance(200);
  Equilibrium e{relax.scene()};
  Particles& particles = e.scene.particles;
  particles.velocity.setZero();
  Simulation forces(e.scene, lab_implementation());
  std::vector<int> free;
  for (int i = 0; i < particles.size(); ++i)
    if (!particles.pinned[std::size_t(i)]) free.push_back(i);
  const Vectors zero = Vectors::Zero(2, particles.size());
  double previous = std::numeric_limits<double>::infinity();
  for (int n = 0; n < 10; ++n) {
    const Vectors& a = forces.acceleration(particles.position, zero);
    Eigen::VectorXd force(2 * Eigen::Index(free.size()));
    e.residual = 0.0;
    for (std::size_t j = 0; j < free.size(); ++j) {
      force.segment<2>(2 * Eigen::Index(j)) = particles.mass[free[j]] * a.col(free[j]);
      e.residual = std::max(e.residual, a.col(free[j]).norm());
    }
    // Stop at rounding: a step that no longer shrinks the residual tenfold gains nothing.
    if (e.residual > 0.1 * previous || e.residual == 0.0) break;
    previous = e.residual;
    const LinearModel model =
        linearise(e.scene.springs, particles.position, particles.mass, particles.pinned);
    const Eigen::VectorXd step = model.stiffness.ldlt().solve(force);
    for (std::size_t j = 0; j < free.size(); ++j)
      particles.position.col(free[j]) += step.segment<2>(2 * Eigen::Index(j));
    e.newton_steps = n + 1;
  }
  return e;
}

namespace {

// `equilibrium`: the springs' lengths there.
bool grows(const Scene& start, const std::vector<double>& equilibrium, const std::string& method,
           double h, long steps) {
  Scene scene = start;
  scene.parameters.step = h;
  scene.parameters.integrator = integrator_of(method);
  // Only finiteness is watched (every step): the energy check would cost as much as the step.
  Simulation sim(std::move(scene), implementation_of(method), DivergenceLimits{1e300, 1 << 30});
  // The strain of an oscillation passes through zero: judge the envelope, the largest strain
  // of each of 100 blocks of the run.
  const long block = std::max(1L, steps / 100);
  std::vector<double> envelope;
  double largest = 0.0;
  try {
    for (long n = 1; n <= 100 * block; ++n) {
      sim.step();
      largest = std::max(
          largest, largest_strain(sim.scene().springs, sim.particles().position, equilibrium));
      if (n % block != 0) continue;
      envelope.push_back(largest);
      largest = 0.0;
      const double first = envelope.front();
      if (envelope.back() > 1e3 * first) return true;  // far beyond anything a stable step does
      // Decayed ten-thousandfold: stable, and stopped before noise decides the comparison
      // below (task 4's Verlet settles its velocity to 1e-12 of |r|/h, which leaves a floor
      // near 1e-12 m of strain).
      if (envelope.back() < 1e-4 * first) return false;
    }
  } catch (const DivergenceError&) {
    return true;
  } catch (const NotImplemented&) {
    return true;  // the student's task is not written: nothing to measure (see the page)
  }
  return *std::max_element(envelope.begin() + 90, envelope.end()) >
         *std::max_element(envelope.begin() + 40, envelope.begin() + 50);
}

template <class Unstable>
double bisect(double lo, double hi, int iterations, Unstable&& unstable) {
  for (int i = 0; i < iterations; ++i) {
    const double mid = std::sqrt(lo * hi);
    (unstable(mid) ? hi : lo) = mid;
  }
  return std::sqrt(lo * hi);
}

std::string source_name(LimitSource source) {
  switch (source) {
    case LimitSource::exact_formula:
      return "exact (formula)";
    case LimitSource::bisection:
      return "exact (bisection of the step matrix)";
    case LimitSource::modal_estimate:
      return "estimate (per mode, with each mode's own damping)";
    case LimitSource::lower_bound:
      return "lower bound (2/omega_bound: certainly stable, the limit is larger)";
    case LimitSource::no_limit:
      return "none";
    case LimitSource::not_computed:
      return "not computed";
  }
  return "";
}

// Steps for growth at 0.5 % beyond the limit to reach e³ (at least 4000, at most 400000).
long run_length(const LinearModel& model, const std::string& method, double h_c) {
  const double growth = std::log(step_growth_factor(model, method, 1.005 * h_c));
  return std::clamp(long(3.0 / std::max(growth, 1e-12)), 4000L, 400000L);
}

bool is_linear_scene(const Scenario& s) {
  return !s.params.gravity.enabled;
}

// The system eigenvalues of a model without the rigid ones, solved once: explicit Euler's and
// RK4's limits and growth factors follow from them alone (stability.hpp).
struct Spectrum {
  std::vector<std::complex<double>> lambda;

  explicit Spectrum(const LinearModel& model) : lambda(deforming_eigenvalues(model)) {}
  double limit(const std::string& method) const { return polynomial_critical_step(lambda, method); }
  double growth(const std::string& method, double h) const {  // per step, the largest
    return polynomial_growth_factor(lambda, method, h);
  }
};

// Steps for growth at (1 + δ)·h_c to reach e³, at least 4000. The Verlet methods and
// symplectic Euler grow by 1.2–1.3 a step 2 % beyond their limits on the fabric
// (step_growth_factor, 15 s of eigen-solve each, too slow to ask every run), so 4000 is ample.
long fabric_run_length(const std::optional<Spectrum>& spectrum, const std::string& method,
                       double h) {
  if (method != "explicit-euler" && method != "rk4") return 4000;
  return std::max(4000L, long(3.0 / std::max(std::log(spectrum->growth(method, h)), 1e-15)));
}

std::string percent(double x) {
  return number(100.0 * x, 2) + " %";
}

// The fabric about its hanging equilibrium: its linear model, its spectrum (not in --quick), the
// words saying so, and the perturbed start and spring lengths the runs use.
struct Hanging {
  LinearModel model;
  std::optional<Spectrum> spectrum{};
  std::string about{};
  Scene start{};
  std::vector<double> length{};
};

// (1 ± δ)·h_c tested by runs of `steps` from the hanging equilibrium; in the full study the
// bracket is then bisected to ±0.25 %; when theory is off by more than δ, bisected from h_c/2.
void measure_near(StepLimit& out, const Hanging& hanging, const std::string& method, double h_c,
                  double delta, long steps, const StudyOptions& options) {
  const std::string runs = ", on runs of " + std::to_string(steps) +
                           " steps from a 1e-6 m random perturbation of the hanging equilibrium";
  const auto unstable = [&](double h) {
    return grows(hanging.start, hanging.length, method, h, steps);
  };
  double lo = (1 - delta) * h_c, hi = (1 + delta) * h_c;
  if (!unstable(lo) && unstable(hi)) {
    const int iterations = options.quick ? 0 : int(std::ceil(std::log2(delta / 0.0025)));
    for (int i = 0; i < iterations; ++i)
      (unstable(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    out.how = "bracket: stable at (1 − " + percent(delta) + ")·h_c, unstable at (1 + " +
              percent(delta) + ")·h_c" +
              (iterations > 0 ? ", then bisected " + std::to_string(iterations) + " times" : "") +
              runs;
  } else {  // theory is off by more than δ (an estimate): bisect from h_c/2 … 2h_c
    lo = bisect(0.5 * h_c, 2.0 * h_c, 9, unstable);
    hi = lo * std::pow(4.0, 1.0 / 512.0), lo /= std::pow(4.0, 1.0 / 512.0);
    out.how = "bisection from h_c/2 … 2h_c (theory is not within ±" + percent(delta) + ")" + runs;
  }
  out.measured = 0.5 * (lo + hi);
  out.half_width = 0.5 * (hi - lo);
}

// One method's limit on the hanging fabric: theory, then runs where they fit the budget of steps.
// Explicit Euler's growth beyond its limit is tiny (its critical modes are lightly damped,
// ζ ≈ 0.004): it is measured only when its runs fit, which on the fabric they do not (millions of
// steps).
StepLimit hanging_limit(const Scenario& s, const std::string& method, const Hanging& hanging,
                        const StudyOptions& options, Progress& progress) {
  constexpr long budget = 200000;  // steps a run may take: a few seconds
  const std::optional<Spectrum>& spectrum = hanging.spectrum;
  StepLimit out;
  out.scene = s.name;
  out.method = method;
  out.about = hanging.about;
  const std::string integrator = integrator_of(method);
  if (const std::string missing = not_written(method); !missing.empty()) {
    out.how = "not measured: " + missing;
    return out;
  }
  const bool by_eigenvalues = integrator == "explicit-euler" || integrator == "rk4";
  if (by_eigenvalues && !spectrum) {
    out.source = "not computed in --quick (a 1520×1520 nonsymmetric eigen-solve)";
    return out;
  }
  const CriticalStep theory =
      by_eigenvalues ? CriticalStep{spectrum->limit(integrator), LimitSource::exact_formula}
                     : critical_step_of(hanging.model, integrator, s.params.xpbd.substeps);
  out.theory = theory.step;
  out.source = source_name(theory.source);
  const double h_c = theory.step;
  if (std::isinf(h_c) || h_c <= 0.0) return out;
  progress.begin(s.name + ": critical step of " + shown(method));
  const double delta = 0.02;
  const long steps = fabric_run_length(spectrum, integrator, (1 + delta) * h_c);
  if (steps > budget) {
    out.how = "not measured: 2 % beyond the limit a deviation grows by a factor 1 + " +
              number(spectrum->growth(integrator, (1 + delta) * h_c) - 1.0) +
              " a step, so reaching e³ would take " + std::to_string(steps) + " steps (" +
              number(double(steps) * h_c / 3600.0, 2) + " h of simulated time)";
    return out;
  }
  measure_near(out, hanging, method, h_c, delta, steps, options);
  progress.done(double(steps) * 10.0 * 400.0);
  return out;
}

// The fabric: theory about its hanging equilibrium, and (1 ± δ)·h_c tested by runs from it.
std::vector<StepLimit> hanging_critical_steps(const Scenario& s, const StudyOptions& options,
                                              Progress& progress) {
  progress.begin(s.name + ": hanging equilibrium and its system eigenvalues");
  const double started = now();
  const Equilibrium equilibrium = hanging_equilibrium(s.params);
  Hanging hanging{.model = linearise(equilibrium.scene)};
  // --quick skips the eigen-solve (5–15 s on this machine): its fabric checks are the Verlet
  // methods' exact limits, which need only the symmetric K.
  if (!options.quick) hanging.spectrum.emplace(hanging.model);
  const std::optional<Spectrum>& spectrum = hanging.spectrum;
  hanging.about =
      "about its hanging equilibrium (implicit Euler at h = 0.05 s for 10 s, then " +
      std::to_string(equilibrium.newton_steps) + " Newton steps on the force balance: largest " +
      "acceleration left " + number(equilibrium.residual) + " m/s²" +
      (spectrum ? "; with its " + std::to_string(spectrum->lambda.size()) + " system eigenvalues"
                : "") +
      ", " + seconds(now() - started) + ")";
  progress.done(3e8);
  hanging.start = perturbed(equilibrium.scene);
  hanging.length = lengths(equilibrium.scene);
  std::vector<StepLimit> limits;
  for (const std::string& method : study_methods(options))
    limits.push_back(hanging_limit(s, method, hanging, options, progress));
  return limits;
}

}  // namespace

double critical_work(const Scenario& s, const StudyOptions& options) {
  const double particles = double(s.params.rows * s.params.cols);
  const double iterations = options.quick ? 14 : 16;
  const double methods = options.student ? 7 : 5;  // those with a finite limit
  if (is_linear_scene(s)) return methods * iterations * 60000.0 * particles;
  return 3e8 + methods * 4000.0 * 10.0 * particles;  // the eigen-solve, about 8 s, and the runs
}

std::vector<StepLimit> critical_steps(const Scenario& s, const StudyOptions& options,
                                      Progress& progress) {
  if (!is_linear_scene(s)) return hanging_critical_steps(s, options, progress);
  const StabilityReport report = stability_report(s.params, lab_implementation());
  std::vector<StepLimit> limits;
  const Scene rest = at_rest(s.params);
  const Scene start = perturbed(rest);
  const std::vector<double> length = lengths(rest);
  const LinearModel model = linearise_at_rest(s.params, lab_implementation());
  std::vector<StabilityReport::Limit> methods = report.limits;
  for (const std::string& method : study_methods(options))  // the student's: their method's limit
    for (const auto& limit : report.limits)
      if (is_students(method) && limit.integrator == integrator_of(method))
        methods.push_back({method, limit.critical});
  for (const auto& limit : methods) {
    StepLimit out;
    out.scene = s.name;
    out.method = limit.integrator;
    out.theory = limit.critical.step;
    out.source = source_name(limit.critical.source);
    out.about = "at rest";
    const double h_c = limit.critical.step;
    if (std::isinf(h_c) || h_c <= 0.0) {
      limits.push_back(out);
      continue;
    }
    if (const std::string missing = not_written(out.method); !missing.empty()) {
      out.how = "not measured: " + missing;
      limits.push_back(out);
      continue;
    }
    progress.begin(s.name + ": critical step of " + shown(out.method));
    const long steps = run_length(model, integrator_of(out.method), h_c);
    out.measured = bisect(0.5 * h_c, 2.0 * h_c, options.quick ? 14 : 16,
                          [&](double h) { return grows(start, length, out.method, h, steps); });
    out.how = "bisection on runs of " + std::to_string(steps) +
              " steps from a 1e-6 m random perturbation of the rest state";
    progress.done(critical_work(s, options) / (options.student ? 7.0 : 5.0));
    limits.push_back(out);
  }
  return limits;
}

}  // namespace springlab::tradeoff
