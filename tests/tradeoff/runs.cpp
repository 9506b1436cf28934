// One run: a method at one step (or tolerance) on one scene, its error sampled at the output
// times, then timed again without the sampling (so that measuring does not count as work).
#include "measure.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace springlab::tradeoff {

namespace odeint = boost::numeric::odeint;

namespace {

// Far beyond any motion of the lab's scenes (1 m grid spacing): a run this wrong has blown up
// even if the divergence watch has not fired yet.
constexpr double error_bound = 10.0;  // m

Run start_run(const Scenario& s, const std::string& method, double h, double tolerance) {
  Run run;
  run.scene = s.name;
  run.method = method;
  run.h = h;
  run.tolerance = tolerance;
  return run;
}

// Output time j is compared every `stride` reference samples, `per` steps apart.
std::size_t sample_stride(const Scenario& s, long per, double h) {
  return std::max<std::size_t>(1, std::size_t(std::lround(double(per) * h / s.reference.time[1])));
}

// Compares the state at output time j (every `stride` reference samples) with the reference.
void observe(const Scenario& s, Run& run, std::size_t j, const Vectors& r, double energy,
             bool keep_energy) {
  const double error = position_error(r, s.reference.position[j]);
  run.max_error = std::max(run.max_error, error);
  run.end_error = error;
  run.energy_error =
      std::max(run.energy_error, std::abs(energy - s.reference.energy[j]) / s.energy_scale);
  if (keep_energy) run.energy.push_back(energy);
  if (!run.stable) return;  // the first reason stands (the lab step's runs go on for the figure)
  if (!std::isfinite(error) || error > error_bound) {
    run.stable = false;
    run.unstable_why =
        "error above " + number(error_bound) + " m at t = " + number(s.reference.time[j]) + " s";
  } else if (energy - s.reference.energy[j] > s.energy_scale) {
    // Dampers only take energy out: a run that gains more than the scene ever holds is growing
    // without bound, even where the divergence watch (10^4 times) has not fired yet.
    run.stable = false;
    run.unstable_why =
        "gained more energy than the scene holds by t = " + number(s.reference.time[j]) + " s";
  }
}

Run measure_kit(const Scenario& s, const std::string& method, double h, bool keep_energy) {
  SceneParameters p = s.params;
  set_number(p, "step", h);
  set_parameter(p, "integrator", integrator_of(method));
  Run run = start_run(s, method, h, 0.0);
  std::optional<Simulation> made;
  try {
    made.emplace(p, implementation_of(method));
  } catch (const std::exception& e) {  // the student's springs refused, or not written
    run.stable = false;
    run.unstable_why = e.what();
    return run;
  }
  Simulation& sim = *made;
  const long per = steps_between_samples(s.reference.time[1], h);
  const std::size_t stride = sample_stride(s, per, h);
  try {
    for (std::size_t j = 0; j < s.reference.time.size() && (run.stable || keep_energy);
         j += stride) {
      if (j > 0) sim.advance(per);
      observe(s, run, j, sim.particles().position, sim.diagnostics().total(), keep_energy);
    }
    sim.check();
  } catch (const DivergenceError& e) {
    run.stable = false;
    run.unstable_why = e.what();
  } catch (const std::exception& e) {  // NotImplemented: the student's task is not written yet
    run.stable = false;
    run.unstable_why = e.what();
  }
  run.evaluations = sim.force_evaluations();
  run.steps = sim.steps_taken();
  return run;
}

Run measure_odeint_rk4(const Scenario& s, double h, bool keep_energy) {
  Simulation sim(s.params, lab_implementation());
  const Vectors start = sim.particles().position;
  OdeintState y = odeint_state(sim.particles());
  OdeintSystem system(sim);
  Run run = start_run(s, odeint_rk4, h, 0.0);
  const long per = steps_between_samples(s.reference.time[1], h);
  const std::size_t stride = sample_stride(s, per, h);
  OdeintRk4 stepper;
  for (std::size_t j = 0; j < s.reference.time.size() && (run.stable || keep_energy); j += stride) {
    if (j > 0) odeint::integrate_n_steps(stepper, std::ref(system), y, 0.0, h, per);
    if (j > 0) run.steps += per;
    observe(s, run, j, odeint_positions(y),
            total_energy(sim, odeint_positions(y), odeint_velocities(y), start), keep_energy);
  }
  run.evaluations = sim.force_evaluations();
  return run;
}

Run measure_dopri5(const Scenario& s, double tolerance) {
  Simulation sim(s.params, lab_implementation());
  const Vectors start = sim.particles().position;
  OdeintState y = odeint_state(sim.particles());
  OdeintSystem system(sim);
  Run run = start_run(s, odeint_dopri5, 0.0, tolerance);
  std::size_t j = 0;
  auto watch = [&](const OdeintState& state, double) {
    const Vectors r = odeint_positions(state);
    observe(s, run, j++, r, total_energy(sim, r, odeint_velocities(state), start), false);
  };
  run.steps = long(odeint::integrate_times(
      odeint::make_dense_output(tolerance, tolerance, OdeintDopri5()), std::ref(system), y,
      s.reference.time.begin(), s.reference.time.end(), s.params.step, watch));
  run.h = s.params.duration / double(std::max(1L, run.steps));
  run.evaluations = sim.force_evaluations();
  return run;
}

// The same run without sampling, for its wall time alone. Diverging runs are not timed.
double time_once(const Scenario& s, const std::string& method, double h, double tolerance) {
  const long steps = std::lround(s.params.duration / h);
  if (method == odeint_rk4 || method == odeint_dopri5) {
    Simulation sim(s.params, lab_implementation());
    OdeintState y = odeint_state(sim.particles());
    OdeintSystem system(sim);
    const double start = now();
    if (method == odeint_rk4)
      odeint::integrate_n_steps(OdeintRk4(), std::ref(system), y, 0.0, h, steps);
    else
      odeint::integrate_adaptive(odeint::make_dense_output(tolerance, tolerance, OdeintDopri5()),
                                 std::ref(system), y, 0.0, s.params.duration, s.params.step);
    return now() - start;
  }
  SceneParameters p = s.params;
  set_number(p, "step", h);
  set_parameter(p, "integrator", integrator_of(method));
  Simulation sim(p, implementation_of(method));
  const double start = now();
  sim.advance(steps);
  return now() - start;
}

}  // namespace

int k_min(const Scenario& s, const StudyOptions& options) {
  return s.name == "fabric" ? options.k_min_fabric : options.k_min;
}

std::vector<std::string> kit_methods() {
  return integrator_names();
}

std::vector<std::string> study_methods(const StudyOptions& options) {
  std::vector<std::string> methods = kit_methods();
  if (options.student) {
    methods.push_back(yours + "explicit-euler");
    methods.push_back(yours + "verlet");
  }
  return methods;
}

Run run_method(const Scenario& s, const std::string& method, double h, double tolerance,
               const StudyOptions& options) {
  const bool keep_energy = std::abs(h - s.params.step) < 1e-12 && method != odeint_dopri5;
  Run run = method == odeint_dopri5 ? measure_dopri5(s, tolerance)
            : method == odeint_rk4  ? measure_odeint_rk4(s, h, keep_energy)
                                    : measure_kit(s, method, h, keep_energy);
  run.wall = std::numeric_limits<double>::quiet_NaN();
  if (!run.stable) return run;
  run.wall = std::numeric_limits<double>::infinity();
  for (int i = 0; i < options.repeats; ++i)
    run.wall = std::min(run.wall, time_once(s, method, h, tolerance));
  return run;
}

double run_work(const Scenario& s, const std::string& method, double h, double duration) {
  // Force evaluations a step, roughly, and implicit Euler's matrix work as evaluations.
  double per_step = 1.0;
  if (integrator_of(method) == "verlet") per_step = 5.0;
  if (method == "xpbd") per_step = 0.3 * s.params.xpbd.substeps * s.params.xpbd.iterations;
  if (method == "rk4" || method == odeint_rk4) per_step = 4.0;
  if (method == "implicit-euler") per_step = 12.0;
  return per_step * duration / h * double(s.params.rows * s.params.cols);
}

std::vector<Run> run_scene(const Scenario& s, const StudyOptions& options, Progress& progress) {
  std::vector<Run> runs;
  std::vector<std::string> methods = study_methods(options);
  methods.push_back(odeint_rk4);
  const double repeats = 1.0 + options.repeats;
  for (const std::string& method : methods) {
    for (int k = k_min(s, options); k <= options.k_max; ++k) {
      const double h = std::ldexp(s.params.step, k);
      progress.begin(s.name + ": " + shown(method) + " at h = " + number(h) + " s");
      runs.push_back(run_method(s, method, h, 0.0, options));
      progress.done(repeats * run_work(s, method, h, options.duration));
    }
  }
  for (const double tolerance : options.tolerances) {
    progress.begin(s.name + ": " + odeint_dopri5 + " at tolerance " + number(tolerance));
    runs.push_back(run_method(s, odeint_dopri5, 0.0, tolerance, options));
    progress.done(repeats * run_work(s, odeint_dopri5, 0.01, options.duration));
  }
  return runs;
}

double evaluation_time(const Scenario& s) {
  Simulation sim(s.params, lab_implementation());
  const Vectors r = sim.particles().position, v = sim.particles().velocity;
  double best = std::numeric_limits<double>::infinity();
  const int batch = std::max(10, 200000 / (s.params.rows * s.params.cols));
  for (int repeat = 0; repeat < 5; ++repeat) {
    const double start = now();
    for (int i = 0; i < batch; ++i)
      sim.acceleration(r, v);
    best = std::min(best, (now() - start) / batch);
  }
  return best;
}

double step_cost(const Scenario& s, const std::string& method) {
  SceneParameters p = s.params;
  set_parameter(p, "integrator", method);
  Simulation sim(p, lab_implementation());
  sim.advance(20);  // past the start-up step, CG warm-started
  const int batch = std::max(5, 20000 / (p.rows * p.cols));
  std::vector<double> ratios;
  for (int round = 0; round < 7; ++round) {
    // A batch of steps, then as many evaluations at the state reached: measured moments apart,
    // so a busy machine slows both alike and their ratio holds.
    double start = now();
    sim.advance(batch);
    const double step = now() - start;
    const Vectors r = sim.particles().position, v = sim.particles().velocity;
    start = now();
    for (int i = 0; i < batch; ++i)
      sim.acceleration(r, v);
    ratios.push_back(step / (now() - start));
  }
  std::nth_element(ratios.begin(), ratios.begin() + 3, ratios.end());
  return ratios[3];
}

}  // namespace springlab::tradeoff

namespace springlab::tradeoff {

long cg_product_bound(const Scene& scene, double h, double tolerance, double* condition) {
  const Eigen::VectorXd& m = scene.particles.mass;
  Eigen::VectorXd spring_load = Eigen::VectorXd::Zero(m.size());  // Σ_{s ∋ i} (h b + h² k)
  for (const Spring& s : scene.springs) {
    const double w = h * s.b + h * h * s.k;
    spring_load[s.p] += w;
    spring_load[s.q] += w;
  }
  const double lowest = m.minCoeff();
  const double highest = m.maxCoeff() + 2.0 * spring_load.maxCoeff();
  // Jacobi scaling by a diagonal D within [lowest, highest]: D^-1/2 A D^-1/2 has its eigenvalues
  // in [lowest / highest, highest / lowest].
  const double kappa = (highest / lowest) * (highest / lowest);
  if (condition) *condition = kappa;
  const double root = std::sqrt(kappa);
  const double rate = (root - 1.0) / (root + 1.0);
  if (rate <= 0.0) return 2;  // A a multiple of the identity: one iteration solves it
  return 1 + long(std::ceil(std::log(2.0 * root / tolerance) / std::log(1.0 / rate)));
}

SolverCount count_solver_work(const Scenario& s, const std::string& method, long steps) {
  SceneParameters p = s.params;
  set_parameter(p, "integrator", method);
  Simulation sim(p, lab_implementation());
  SolverCount count;
  count.products_allowed =
      cg_product_bound(sim.scene(), p.step, implicit_euler_tolerance, &count.condition_bound);
  long before = sim.integrator().solver_work().products;
  for (long n = 0; n < steps; ++n) {
    sim.step();
    const SolverWork work = sim.integrator().solver_work();
    count.most_products = std::max(count.most_products, work.products - before);
    before = work.products;
  }
  const SolverWork total = sim.integrator().solver_work();
  count.steps = steps;
  count.mean_products = double(total.products) / double(steps);
  count.factorisations = total.factorisations;
  return count;
}

}  // namespace springlab::tradeoff
