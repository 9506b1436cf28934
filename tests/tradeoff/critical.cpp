// Critical steps: theory from stability.hpp, and measured by bisection on the step.
//
// Two masses and the grid: measured where theory applies, on the linearised motion. The scene
// starts at rest with every particle moved randomly by 1e-6 m (every mode excited, the motion
// linear); a step counts as unstable when the largest spring strain over the last tenth of the
// run exceeds that over the tenth before its middle, so the fastest-growing (or slowest-decaying)
// mode decides (a run that decays ten-thousandfold first is stable). Near its limit a method's
// growth per step is tiny (explicit Euler: about 2ζ²ε per step at ε beyond it), so the run length
// comes from stability.hpp's step_growth_factor: long enough for growth 0.5 % beyond the limit to
// reach e³.
//
// The fabric: its rest state is not an equilibrium (gravity pulls it down and stretches it), so
// the linear theory at rest does not describe its run. Measured instead is the largest step at
// which the scene's own 5.12 s run survives the divergence watch: what a student would observe.
#include "measure.hpp"
#include "springlab/errors.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace springlab::tradeoff {

namespace {

double largest_strain(const std::vector<Spring>& springs, const Vectors& r) {
  double largest = 0.0;
  for (const Spring& s : springs)
    largest = std::max(largest, std::abs((r.col(s.p) - r.col(s.q)).norm() - s.rest_length));
  return largest;
}

Scene perturbed_rest(SceneParameters p) {
  p.displaced = "none";
  Scene scene = build_scene(p, lab_implementation());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> offset(-1e-6, 1e-6);
  for (int i = 0; i < scene.particles.size(); ++i)
    if (!scene.particles.pinned[std::size_t(i)])
      scene.particles.position.col(i) += Vec2(offset(random), offset(random)) * p.spacing;
  return scene;
}

bool grows(const Scene& start, const std::string& method, double h, long steps) {
  Scene scene = start;
  scene.parameters.step = h;
  scene.parameters.integrator = method;
  Simulation sim(std::move(scene), lab_implementation(), DivergenceLimits{1e300, 1});
  // The strain of an oscillation passes through zero: judge the envelope, the largest strain
  // of each of 100 blocks of the run.
  const long block = std::max(1L, steps / 100);
  std::vector<double> envelope;
  double largest = 0.0;
  try {
    for (long n = 1; n <= 100 * block; ++n) {
      sim.step();
      largest = std::max(largest, largest_strain(sim.scene().springs, sim.particles().position));
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
  }
  return *std::max_element(envelope.begin() + 90, envelope.end()) >
         *std::max_element(envelope.begin() + 40, envelope.begin() + 50);
}

bool survives(const Scenario& s, const std::string& method, double h) {
  SceneParameters p = s.params;
  set_number(p, "step", h);
  set_parameter(p, "integrator", method);
  try {
    Simulation sim(p, lab_implementation());
    sim.advance(std::lround(p.duration / h));
    sim.check();
    return true;
  } catch (const DivergenceError&) {
    return false;
  }
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
      return "estimate (frequency bounds)";
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

}  // namespace

double critical_work(const Scenario& s, const StudyOptions& options) {
  const double particles = double(s.params.rows * s.params.cols);
  const double iterations = options.quick ? 14 : 16;
  return is_linear_scene(s) ? 5 * iterations * 60000.0 * particles
                            : 5 * 10 * 4 * s.params.duration / 0.01 * particles;
}

std::vector<StepLimit> critical_steps(const Scenario& s, const StudyOptions& options,
                                      Progress& progress) {
  const StabilityReport report = stability_report(s.params, lab_implementation());
  std::vector<StepLimit> limits;
  const Scene start = perturbed_rest(s.params);
  const LinearModel model =
      is_linear_scene(s) ? linearise_at_rest(s.params, lab_implementation()) : LinearModel{};
  for (const auto& limit : report.limits) {
    StepLimit out;
    out.scene = s.name;
    out.method = limit.integrator;
    out.theory = limit.critical.step;
    out.source = source_name(limit.critical.source);
    const double h_c = limit.critical.step;
    if (std::isinf(h_c) || (h_c <= 0.0 && is_linear_scene(s))) {
      limits.push_back(out);
      continue;
    }
    progress.begin(s.name + ": critical step of " + out.method);
    if (is_linear_scene(s)) {
      const long steps = run_length(model, out.method, h_c);
      out.measured = bisect(0.5 * h_c, 2.0 * h_c, options.quick ? 14 : 16,
                            [&](double h) { return grows(start, out.method, h, steps); });
      out.how = "bisection on runs of " + std::to_string(steps) +
                " steps from a 1e-6 m random perturbation of the rest state";
    } else {
      // Bracketed by the sweep's steps, not by theory: the hanging cloth is not the cloth at rest.
      const double lo = std::ldexp(s.params.step, k_min(s, options));
      const double hi = std::ldexp(s.params.step, options.k_max);
      if (survives(s, out.method, hi) || !survives(s, out.method, lo)) {
        out.how = "not bracketed by the sweep's steps";
        limits.push_back(out);
        continue;
      }
      out.measured = bisect(lo, hi, 12, [&](double h) { return !survives(s, out.method, h); });
      out.how = "largest step whose " + number(s.params.duration) +
                " s run of the scene passes the divergence watch (bisection)";
    }
    progress.done(critical_work(s, options) / 5.0);
    limits.push_back(out);
  }
  return limits;
}

}  // namespace springlab::tradeoff
