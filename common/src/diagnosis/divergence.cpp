// The diagnosis of a diverged run (divergence.hpp): a replay with the same code that watches the
// laws the forces must keep, then the step limit of the method.
#include "springlab/divergence.hpp"
#include "diagnosis/measured_model.hpp"
#include "support/numbers.hpp"

#include "springlab/cli_values.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/errors.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/scene.hpp"
#include "springlab/simulation.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <complex>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace springlab {
namespace detail {

// The two things a replay needs of a Simulation that no one else should use.
struct ReplayAccess {
  static void start_at(Simulation& sim, double time) { sim.start_time_ = time; }
  static void watch_forces(Simulation& sim, Simulation::ForceWatch watch) {
    sim.force_watch_ = std::move(watch);
  }
};

}  // namespace detail

namespace {

using internal::infinity;
using internal::measured_model;
using internal::model_gap;
using internal::significant;
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// A component below rounding of the other (1e-12 of the length) is written 0.
std::string vector_text(const Vec2& v) {
  const auto component = [&](double x) { return std::abs(x) <= 1e-12 * v.norm() ? 0.0 : x; };
  std::string text = "(";  // appended: GCC 12 at -O3 warns falsely about "(" + std::string
  return text.append(significant(component(v.x())))
      .append(", ")
      .append(significant(component(v.y())))
      .append(")");
}

std::string method_name(std::string_view integrator) {
  if (integrator == "explicit-euler") return "explicit Euler";
  if (integrator == "symplectic-euler") return "symplectic Euler";
  if (integrator == "verlet") return "Verlet";
  if (integrator == "velocity-verlet") return "velocity Verlet";
  if (integrator == "rk4") return "RK4";
  if (integrator == "implicit-euler") return "implicit Euler";
  if (integrator == "xpbd") return "XPBD";
  return std::string(integrator);
}

bool is_grid(const Scene& scene) {
  return scene.particles.size() == scene.parameters.rows * scene.parameters.cols;
}

// The grid at rest (no particle displaced) for a grid scene, else the particles where they are.
Vectors rest_positions(const Scene& scene) {
  if (!is_grid(scene)) return scene.particles.position;
  const SceneParameters& p = scene.parameters;
  Vectors r(2, scene.particles.size());
  for (int i = 0; i < scene.particles.size(); ++i)
    r.col(i) = grid_position(i / p.cols, i % p.cols, p.spacing);
  return r;
}

// The springs' forces alone and the dampers' alone, as the kit's model computes them, without a
// copy of the task code (a student release ships this file): the model's fast path
// (grid_forces.hpp) on the same springs with b = 0 and with k = 0, for a scene whose springs are
// whole families on its grid, as every lab scene's are; otherwise minus the gradients of the
// spring energy Σ ½ k (L − ℓ0)² in r and of the dissipation Σ ½ b |v_p − v_q|² in v, by central
// differences, spring by spring.
class SpringsApart {
 public:
  SpringsApart(const std::vector<Spring>& springs, int rows, int cols)
      : springs_(springs), springs_only_(springs), dampers_only_(springs), particles_(rows * cols) {
    for (Spring& s : springs_only_)
      s.b = 0.0;
    for (Spring& s : dampers_only_)
      s.k = 0.0;
    spring_path_ = GridForces::of(springs_only_, rows, cols);
    damper_path_ = GridForces::of(dampers_only_, rows, cols);
  }

  void forces(const Vectors& r, const Vectors& v, Vectors& spring, Vectors& damper) {
    if (spring_path_ && damper_path_ && r.cols() == particles_) {
      spring_path_->compute(r, v, spring);
      damper_path_->compute(r, v, damper);
      return;
    }
    spring.setZero(2, r.cols());
    damper.setZero(2, r.cols());
    for (const Spring& s : springs_) {
      const auto energy = [&](const Vec2& d) {
        const double stretch = d.norm() - s.rest_length;
        return 0.5 * s.k * stretch * stretch;
      };
      const auto dissipation = [&](const Vec2& dv) { return 0.5 * s.b * dv.squaredNorm(); };
      // Both depend on r_p − r_q (v_p − v_q) alone: the force on q is minus that on p.
      const Vec2 fs = -gradient(energy, r.col(s.p) - r.col(s.q));
      const Vec2 fd = -gradient(dissipation, v.col(s.p) - v.col(s.q));
      spring.col(s.p) += fs;
      spring.col(s.q) -= fs;
      damper.col(s.p) += fd;
      damper.col(s.q) -= fd;
    }
  }

 private:
  std::vector<Spring> springs_, springs_only_, dampers_only_;
  std::optional<GridForces> spring_path_, damper_path_;
  long particles_;  // rows · cols

  template <typename Function>
  static Vec2 gradient(const Function& f, const Vec2& x) {
    const double h = 1e-6 * std::max(1.0, x.norm());
    Vec2 g;
    for (int i = 0; i < 2; ++i) {
      Vec2 up = x, down = x;
      up[i] += h;
      down[i] -= h;
      g[i] = (f(up) - f(down)) / (2.0 * h);
    }
    return g;
  }
};

// Where only the student's step can be the cause (their forces are the reference's, or measured
// right): what to look at, said alike wherever the diagnosis reaches that verdict.
constexpr const char* euler_step_words =
    "Look at the step itself: explicit_euler_step, equations (1.4) and (1.5), both from the "
    "values at the start of the step.";
// Only the step is the student's here: the springs and dampers are the reference's.
constexpr const char* verlet_step_words =
    "Look at the step itself: verlet_step, handout section 4. With the backward difference "
    "(r_n - r_{n-1})/h in the dampers instead of (4.2) (textbook Verlet) the limit drops to "
    "2(sqrt(1 + zeta^2) - zeta)/omega per mode, below 2/omega_max.";
const Implementation* diagnosis_reference = nullptr;  // set_diagnosis_reference

// Whether the kit's reference diverges on the scene at its h by time `until`: true for the
// reference's own run, nothing where no reference is at hand (a grader's test program) or the
// run is beyond the replay's budget.
std::optional<bool> reference_diverges(const SceneParameters& p, const Implementation& impl,
                                       double until, const DiagnosisBudget& budget) {
  if (impl.student_task == 0) return true;
  if (diagnosis_reference == nullptr) return std::nullopt;
  const long steps = long(std::ceil(until / p.step - 1e-9));
  if (double(p.rows) * double(p.cols) * double(steps) > budget.particle_steps) return std::nullopt;
  DivergenceLimits quiet;
  quiet.diagnose = false;
  try {
    Simulation reference(p, *diagnosis_reference, quiet);
    reference.advance(steps);
    reference.check();
  } catch (const DivergenceError&) {
    return true;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return false;
}

// How many springs the reference makes for the scene, -1 when unknown.
long reference_springs_of(const SceneParameters& p) {
  if (diagnosis_reference == nullptr) return -1;
  try {
    return long(build_scene(p, *diagnosis_reference).springs.size());
  } catch (const std::exception&) {
    return -1;
  }
}

// The largest |L - l0| / l0 of the springs at positions r.
double strain_of(const std::vector<Spring>& springs, const Vectors& r) {
  double largest = 0.0;
  for (const Spring& s : springs)
    if (s.rest_length > 0.0)
      largest = std::max(
          largest, std::abs((r.col(s.p) - r.col(s.q)).norm() - s.rest_length) / s.rest_length);
  return largest;
}

// The least-squares fit F ≈ α·(kit's spring forces) + β·(kit's damper forces) over the forces the
// run's code gave: α = β = 1 for correct forces, -1 for a sign that points the wrong way.
struct SignFit {
  double ss = 0, sd = 0, dd = 0, fs = 0, fd = 0, ff = 0;
  int samples = 0;

  void add(const Vectors& f, const Vectors& s, const Vectors& d) {
    ss += (s.array() * s.array()).sum();
    sd += (s.array() * d.array()).sum();
    dd += (d.array() * d.array()).sum();
    fs += (f.array() * s.array()).sum();
    fd += (f.array() * d.array()).sum();
    ff += (f.array() * f.array()).sum();
    ++samples;
  }
  struct Result {
    bool exact = false;  // the forces are α·spring + β·damper to rounding
    double alpha = 1.0, beta = 1.0;
    bool has_damping = false;
  };
  Result solve() const {
    Result r;
    if (ss <= 0.0 || ff <= 0.0) return r;
    r.has_damping = dd > 1e-12 * ss;
    if (r.has_damping) {
      const double det = ss * dd - sd * sd;
      if (det <= 1e-12 * ss * dd) return r;
      r.alpha = (fs * dd - fd * sd) / det;
      r.beta = (fd * ss - fs * sd) / det;
    } else {
      r.alpha = fs / ss;
    }
    const double residual = ff - 2 * (r.alpha * fs + r.beta * fd) + r.alpha * r.alpha * ss +
                            2 * r.alpha * r.beta * sd + r.beta * r.beta * dd;
    if (!r.has_damping) r.beta = 1.0;
    r.exact = residual <= 1e-8 * ff;
    return r;
  }
};

// A mirror of the grid onto itself: particle i ↔ image[i], x or y reflected about `centre`.
struct Mirror {
  std::string name;  // "left-right", "up-down"
  int axis = 0;      // the coordinate reflected: 0 = x, 1 = y
  double centre = 0.0;
  std::vector<int> image;

  Vec2 reflect(const Vec2& r) const {
    Vec2 m = r;
    m[axis] = 2 * centre - r[axis];
    return m;
  }
  Vec2 reflect_direction(const Vec2& v) const {
    Vec2 m = v;
    m[axis] = -v[axis];
    return m;
  }
  // The largest distance between a particle and the mirror image of its partner, m.
  double mismatch(const Vectors& r) const {
    double worst = 0.0;
    for (std::size_t i = 0; i < image.size(); ++i)
      worst = std::max(worst, (r.col(Eigen::Index(i)) - reflect(r.col(image[i]))).norm());
    return worst;
  }
};

// The mirrors under which the start state, the masses, the pins and gravity are symmetric (to
// rounding); none when the wind or the push acts, whose fields need not be.
std::vector<Mirror> symmetric_mirrors(const Scene& scene) {
  std::vector<Mirror> mirrors;
  const SceneParameters& p = scene.parameters;
  const Particles& particles = scene.particles;
  if (!is_grid(scene) || p.wind.enabled || (p.push_duration > 0 && !p.push.isZero()))
    return mirrors;
  const int n = particles.size();
  const double tolerance = 1e-9 * p.spacing;
  for (int axis = 0; axis < 2; ++axis) {
    if (p.gravity.enabled && p.gravity.acceleration[axis] != 0.0) continue;
    Mirror m;
    m.name = axis == 0 ? "left-right" : "up-down";
    m.axis = axis;
    m.centre = axis == 0 ? 0.5 * (p.cols - 1) * p.spacing : -0.5 * (p.rows - 1) * p.spacing;
    m.image.resize(std::size_t(n));
    bool symmetric = true;
    for (int i = 0; i < n && symmetric; ++i) {
      const int row = i / p.cols, col = i % p.cols;
      const int j =
          axis == 0 ? row * p.cols + (p.cols - 1 - col) : (p.rows - 1 - row) * p.cols + col;
      m.image[std::size_t(i)] = j;
      symmetric =
          (particles.position.col(i) - m.reflect(particles.position.col(j))).norm() <= tolerance &&
          (particles.velocity.col(i) - m.reflect_direction(particles.velocity.col(j))).norm() <=
              tolerance &&
          particles.mass[i] == particles.mass[j] &&
          particles.pinned[std::size_t(i)] == particles.pinned[std::size_t(j)];
    }
    if (symmetric) mirrors.push_back(std::move(m));
  }
  return mirrors;
}

// A spring whose mirror image is not in the list: the likely place of a symmetry broken.
std::string unmatched_spring(const std::vector<Spring>& springs, const Mirror& mirror) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(springs.size());
  for (const Spring& s : springs)
    pairs.emplace_back(std::min(s.p, s.q), std::max(s.p, s.q));
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [p, q] : pairs) {
    const int mp = mirror.image[std::size_t(p)], mq = mirror.image[std::size_t(q)];
    if (!std::binary_search(pairs.begin(), pairs.end(),
                            std::pair{std::min(mp, mq), std::max(mp, mq)}))
      return "the spring between particles " + std::to_string(p) + " and " + std::to_string(q) +
             " has no mirror image (between " + std::to_string(std::min(mp, mq)) + " and " +
             std::to_string(std::max(mp, mq)) + ")";
  }
  return "";
}

// The equations of the spring lists the scene uses.
std::string spring_list_equations(const SceneParameters& p) {
  std::string list = "(2.1), (2.2)";
  if (p.shear.enabled) list += ", (3.1)";
  if (p.bend.enabled) list += ", (5.1)";
  return list;
}

// When the wind's drag, not the springs, sets the critical step: every method takes the drag
// c (w - v) explicitly (implicit Euler and velocity Verlet too), so a motion it alone damps
// grows once h > 2 m / c whatever the springs' method.
std::string drag_words(const Scene& scene, const CriticalStep& c) {
  const SceneParameters& p = scene.parameters;
  if (!p.wind.enabled || p.wind.drag <= 0 || c.source == LimitSource::not_computed) return "";
  const double m = scene.particles.mass.minCoeff();
  const double limit = 2.0 * m / p.wind.drag;
  if (!(limit <= 1.01 * c.step)) return "";
  std::ostringstream out;
  out << "; it is set by the wind's drag c (w - v), not by the springs: " << p.integrator
      << " takes the drag explicitly (external forces are explicit in every integrator), and a "
         "motion the drag alone damps grows unless h < 2 m / c = 2 * "
      << significant(m) << " kg / " << significant(p.wind.drag) << " N*s/m = " << significant(limit)
      << " s";
  return out.str();
}

// Whose forces a step limit is of: the scene's, or the code's own where they differ from the
// formulas about rest (limit_of_forces_that_ran).
std::string whose_forces(const Diagnosis& d) {
  if (d.forces_at_rest != ForcesAtRest::differ) return " on this scene";
  std::ostringstream out;
  out << " for this code's forces, measured about the scene at rest, where they are not those of "
         "(1.1) and (1.2) (with those it would be ";
  if (d.formula_critical.source == LimitSource::no_limit || std::isinf(d.formula_critical.step))
    out << "no limit)";
  else
    out << number_apart(d.formula_critical.step, d.critical.step, 3) << " s)";
  return out.str();
}

// "h = 0.01 s is 2 times the critical step 0.005 s of explicit Euler on this scene" and the like.
std::string step_comparison(const Diagnosis& d, const Scene& scene) {
  const std::string_view integrator = scene.parameters.integrator;
  const int particles = scene.particles.size();
  const std::string method = method_name(integrator);
  const CriticalStep& c = d.critical;
  std::ostringstream out;
  out << "h = " << d.step << " s";
  const auto formula_limit = [&] {
    const CriticalStep& f = d.formula_critical;
    return f.source == LimitSource::no_limit || std::isinf(f.step)
               ? "no critical step"
               : "a critical step of " + significant(f.step) + " s";
  };
  if (d.forces_at_rest == ForcesAtRest::grow) {
    std::ostringstream grows;  // no "h = ..." first: h is not what this is about
    grows << "this code's forces, measured about the scene at rest, make some motion grow as "
             "e^(s t) with s = "
          << significant(d.own_growth_rate) << " 1/s in exact time, at any h (here " << d.step
          << " s); with (1.1) and (1.2)'s forces " << method << " would have " << formula_limit();
    return grows.str();
  }
  if (d.forces_at_rest == ForcesAtRest::differ && c.source == LimitSource::not_computed) {
    out << ": (1.1) and (1.2)'s forces would have " << formula_limit() << " with " << method
        << ", which does not hold for this code: its forces, measured about the scene at rest, "
           "are not theirs";
    return out.str();
  }
  if (c.source == LimitSource::not_computed) {
    out << ": the critical step of " << method << " is not computed for a scene of " << particles
        << " particles (springlab-run --stability computes it up to " << exact_particles_max << ")";
    double guide = infinity;  // the smallest b/k: explicit Euler's limit for one spring (1.6)
    for (const Spring& s : scene.springs)
      if (s.k > 0) guide = std::min(guide, s.b / s.k);
    if (integrator == "explicit-euler" && std::isfinite(guide))
      out << "; as a guide, for one spring it is b/k, equation (1.6), and the smallest b/k of "
             "these springs is "
          << significant(guide) << " s, which h is " << (d.step > guide ? "beyond" : "below");
    return out.str();
  }
  if (c.source == LimitSource::no_limit || std::isinf(c.step)) {
    out << ": " << method << " has no critical step on this scene";
    return out.str();
  }
  if (c.step == 0.0) {
    out << " is beyond every step " << method << " can take" << whose_forces(d)
        << ": some motion of it has no damping, and " << method
        << " makes an undamped motion grow at every h";
  } else {
    const std::string estimate = c.source == LimitSource::modal_estimate ? "an estimate of "
                                 : c.source == LimitSource::lower_bound  ? "a lower bound of "
                                                                         : "";
    if (d.step > c.step)
      out << " is " << number_apart(d.step / c.step, 1.0, 3) << " times " << estimate
          << "the critical step " << number_apart(c.step, d.step, 3) << " s of " << method;
    else
      out << " is below " << estimate << "the critical step " << number_apart(c.step, d.step, 3)
          << " s of " << method;
    out << whose_forces(d);
  }
  // (A growth of 1 or less says nothing of this divergence: Verlet's iteration, whose own limit
  // the step matrix does not see, can be what failed.)
  if (!std::isnan(d.growth) && d.step > c.step && d.growth > 1.0)
    out << " (each step multiplies its fastest-growing motion by " << number_apart(d.growth, 1.0, 4)
        << ")";
  out << drag_words(scene, c);
  return out.str();
}

// The exact critical step of p's integrator for a linear model (the wind's drag added here), and
// in `growth` the growth per step at p's h when beyond it.
CriticalStep model_critical_step(LinearModel model, const SceneParameters& p, double* growth) {
  if (p.wind.enabled) add_drag(model, p.wind.drag);
  if (p.integrator == "explicit-euler" || p.integrator == "rk4") {  // one eigen-solve for both
    const auto lambda = deforming_eigenvalues(model);
    const double critical = polynomial_critical_step(lambda, p.integrator);
    if (growth && p.step > critical)
      *growth = polynomial_growth_factor(lambda, p.integrator, p.step);
    return {critical, LimitSource::exact_formula};
  }
  const CriticalStep critical = critical_step_of(model, p.integrator, p.xpbd.substeps);
  if (growth && p.step > critical.step && p.integrator != "implicit-euler" &&
      p.integrator != "xpbd")
    *growth = step_growth_factor(model, p.integrator, p.step);
  return critical;
}

// The step limit said of a run is the one of the forces that ran (issue 39). Where the code under
// test's forces, measured about rest, are not those of (1.1) and (1.2) there, d keeps the formula's
// limit beside and says of the run only what the measured model shows: motion that grows in exact
// time (no step is the cause), or for explicit Euler and RK4 the limit from the measured model's
// eigenvalues (which need no symmetry of K); the other methods' formulas assume forces that
// conserve momentum and energy, so for them no limit is claimed.
void limit_of_forces_that_ran(Diagnosis& d, const Scene& start, const Implementation& impl,
                              const DiagnosisBudget& budget) {
  const Particles& particles = start.particles;
  if (is_kit_model(impl) || particles.size() > budget.exact_particles ||
      d.critical.source == LimitSource::no_limit)
    return;
  const Vectors rest = rest_positions(start);
  const std::optional<LinearModel> own = measured_model(start, impl, rest);
  if (!own) {
    d.forces_at_rest = ForcesAtRest::not_measured;
    return;
  }
  // Differences of 1e-6 of a spring's length leave about 1e-9 of rounding in K: 1e-6 is far
  // above it and far below any mistake in a formula.
  if (model_gap(*own, linearise(start.springs, rest, particles.mass, particles.pinned)) <= 1e-6) {
    d.forces_at_rest = ForcesAtRest::as_formulas;
    return;
  }
  d.formula_critical = d.critical;
  d.growth = not_a_number;
  // The rigid motions (lambda = 0, which the differences blur to about 1e-7 1/s) left out; a
  // deforming mode grows when Re(lambda) is above the differences' relative error, 1e-6 of it.
  double rate = 0.0;
  for (const std::complex<double>& l : deforming_eigenvalues(*own))
    if (l.real() > 1e-6 * std::abs(l)) rate = std::max(rate, l.real());
  if (rate > 0.0) {  // grows without any integrator: e^{rate t}
    d.forces_at_rest = ForcesAtRest::grow;
    d.own_growth_rate = rate;
    d.critical = {not_a_number, LimitSource::not_computed};
    return;
  }
  d.forces_at_rest = ForcesAtRest::differ;
  const std::string_view method = start.parameters.integrator;
  d.critical = method == "explicit-euler" || method == "rk4"
                   ? model_critical_step(*own, start.parameters, &d.growth)
                   : CriticalStep{not_a_number, LimitSource::not_computed};
}

bool beyond_critical(const Diagnosis& d) {
  return d.critical.source != LimitSource::not_computed && d.step > d.critical.step;
}

}  // namespace

CriticalStep scene_critical_step(const Scene& scene, const DiagnosisBudget& budget,
                                 double* growth) {
  const Particles& particles = scene.particles;
  const SceneParameters& p = scene.parameters;
  if (growth) *growth = not_a_number;
  const auto free = std::count(particles.pinned.begin(), particles.pinned.end(), false);
  if (free == 0) return {infinity, LimitSource::no_limit};
  const Vectors rest = rest_positions(scene);
  if (particles.size() <= budget.exact_particles)  // as stability_report decides
    return model_critical_step(linearise(scene.springs, rest, particles.mass, particles.pinned), p,
                               growth);
  const double w = highest_frequency_bound(scene.springs, rest, particles.mass, particles.pinned);
  double c = damping_rate_bound(scene.springs, particles.mass, particles.pinned);
  const double drag_rate = p.wind.enabled ? p.wind.drag / particles.mass.minCoeff() : 0.0;
  return estimated_critical_step(p.integrator, w, c + drag_rate, drag_rate, p.xpbd.substeps);
}

void set_diagnosis_reference(const Implementation* reference) {
  diagnosis_reference = reference;
}

const Implementation* registered_diagnosis_reference() {
  return diagnosis_reference;
}

Diagnosis diagnose_divergence(const Scene& start, const Implementation& impl, double start_time,
                              long steps, const DiagnosisBudget& budget) {
  const SceneParameters& p = start.parameters;
  const Particles& particles = start.particles;
  const int n = particles.size();
  Diagnosis d;
  d.step = p.step;
  d.critical = scene_critical_step(start, budget, &d.growth);
  limit_of_forces_that_ran(d, start, impl, budget);

  // What the replay watches.
  const bool pinned =
      std::find(particles.pinned.begin(), particles.pinned.end(), true) != particles.pinned.end();
  const bool pushed = p.push_duration > start_time && !p.push.isZero() && p.pushed != "none";
  const bool free_of_outside = !p.gravity.enabled && !p.wind.enabled && !pushed && !pinned;
  const bool gravity_only = p.gravity.enabled && !p.wind.enabled && !pushed && !pinned;
  const std::vector<Mirror> mirrors = symmetric_mirrors(start);
  const double total_mass = particles.mass.sum();
  const Vec2 g = p.gravity.enabled ? p.gravity.acceleration : Vec2::Zero();

  long budget_steps = 0;
  if (n <= budget.particles && steps > 0)
    budget_steps = std::min(steps, long(std::max(1.0, budget.particle_steps / std::max(n, 1))));

  bool start_finite = true;
  SignFit fit;
  const Vec2 p0 = linear_momentum(particles.mass, particles.velocity);
  double momentum_scale =
      (particles.mass.transpose() * particles.velocity.colwise().norm().transpose()).value();
  double momentum_broke = not_a_number, symmetry_broke = not_a_number;
  double gravity_wrong = not_a_number;  // s, when add_gravity first added other than m_i g
  int gravity_particle = -1;
  Vec2 gravity_added = Vec2::Zero(), gravity_spring = Vec2::Zero();  // N
  double energy_doubled = not_a_number, start_energy = 0.0, end_energy = 0.0, reference = 0.0;
  double energy_time = start_time;  // s, when end_energy was measured
  Vec2 momentum_end = p0, deviation_end = Vec2::Zero();
  double asymmetry_end = 0.0, asymmetry_at_break = 0.0;
  const Mirror* broken_mirror = nullptr;
  bool symmetry_window = true;
  double end_time = start_time;
  long replayed = 0;
  // The largest |L - l0| / l0 at the start, and when the energy had doubled.
  const double start_strain = strain_of(start.springs, particles.position);
  double strain_at_growth = not_a_number;
  if (budget_steps > 0) {
    try {
      DivergenceLimits quiet;
      quiet.energy_growth = infinity;
      quiet.energy_check_interval = INT_MAX;
      quiet.diagnose = false;
      Simulation replay(Scene(start), impl, quiet);
      detail::ReplayAccess::start_at(replay, start_time);
      Vectors kit_spring, kit_damper;
      SpringsApart apart(start.springs, p.rows, p.cols);
      long evaluations = 0;
      Vectors spring_forces;
      detail::ReplayAccess::watch_forces(
          replay, [&](int stage, const Vectors& r, const Vectors& v, const Vectors& f) {
            if (stage == 1) {  // what add_gravity added, against m_i g (5.2)
              if (!std::isnan(gravity_wrong) || spring_forces.cols() != f.cols()) return;
              const Vectors added = f - spring_forces;
              for (Eigen::Index i = 0; i < f.cols(); ++i) {
                const Vec2 expected = particles.mass[i] * g;
                const Vec2 error = added.col(i) - expected;
                if (!(error.norm() <= 1e-9 * (expected.norm() + spring_forces.col(i).norm()))) {
                  gravity_wrong = replay.time();
                  gravity_particle = int(i);
                  gravity_added = added.col(i);
                  gravity_spring = spring_forces.col(i);
                  break;
                }
              }
              return;
            }
            spring_forces = f;
            if (++evaluations == 1) start_finite = f.allFinite();
            if (fit.samples >= 400 || !f.allFinite() || !r.allFinite() || !v.allFinite()) return;
            apart.forces(r, v, kit_spring, kit_damper);
            fit.add(f, kit_spring, kit_damper);
          });
      start_energy = replay.diagnostics().total();
      reference = replay.reference_energy();
      const Vectors& r0 = particles.position;
      const int check_every = 8;
      for (long k = 0; k < budget_steps; ++k) {
        ++replayed;  // counted when tried: the run's last step may be the one that fails
        replay.step();
        const Particles& now = replay.particles();
        const double t = replay.time();
        end_time = t;
        momentum_scale =
            std::max(momentum_scale,
                     (now.mass.transpose() * now.velocity.colwise().norm().transpose()).value());
        const Vec2 momentum = linear_momentum(now.mass, now.velocity);
        if (free_of_outside || gravity_only) {
          const Vec2 deviation = momentum - p0 - (t - start_time) * total_mass * g;
          double tolerance = 1e-6 * std::max(momentum_scale, 1e-3 * total_mass * p.spacing);
          if (gravity_only) tolerance += 2 * p.step * total_mass * g.norm();
          if (std::isnan(momentum_broke) && deviation.norm() > tolerance) momentum_broke = t;
          momentum_end = momentum;
          deviation_end = deviation;
        }
        // Symmetry is judged until a particle first moves a grid spacing from where the whole
        // grid moved: a motion that large may break it on its own (a symmetric oscillation can
        // pump an antisymmetric one out of rounding), and one that runs away amplifies the
        // rounding of mirrored sums without bound.
        if (!mirrors.empty()) {
          const Vectors moved = now.position - r0;
          const Vec2 mean = moved.rowwise().mean();
          symmetry_window =
              symmetry_window && (moved.colwise() - mean).colwise().norm().maxCoeff() <= p.spacing;
          for (const Mirror& m : mirrors) {
            if (!broken_mirror && symmetry_window) {
              const double mismatch = m.mismatch(now.position);
              if (mismatch > 1e-6 * p.spacing) {
                symmetry_broke = t;
                broken_mirror = &m;
                asymmetry_at_break = mismatch;
              }
            }
            if (&m == broken_mirror) asymmetry_end = m.mismatch(now.position);
          }
        }
        if (k % check_every == check_every - 1 || k + 1 == budget_steps) {
          end_energy = replay.diagnostics().total();
          energy_time = t;
          if (std::isnan(energy_doubled) && end_energy > 2 * reference) {
            energy_doubled = t;
            strain_at_growth = strain_of(start.springs, now.position);
          }
        }
      }
    } catch (const std::exception&) {
      // The replay diverged too (it ends where the run did) or its code failed: what it saw so far
      // is the evidence.
    }
  }
  d.replayed = end_time - start_time;
  d.replayed_all = budget_steps > 0 && replayed == steps;

  std::ostringstream words;
  const SignFit::Result signs = fit.solve();
  // What the replay could check on this scene, in words.
  std::string kept;
  if (replayed > 0) {
    std::vector<std::string> laws;
    if (free_of_outside) laws.push_back("the total momentum, (2.4)");
    if (gravity_only) laws.push_back("the momentum gravity gives, (5.2)");
    if (!mirrors.empty()) laws.push_back("the mirror symmetry of the start");
    if (fit.samples > 0)
      laws.push_back("the directions of the spring and damper forces, (1.1) and (1.2)");
    for (std::size_t i = 0; i < laws.size(); ++i)
      kept += (i == 0 ? "" : i + 1 == laws.size() ? " and " : ", ") + laws[i];
  }
  const std::string kept_words = kept.empty()
                                     ? "the kit could check no law of the forces here"
                                     : "the forces kept what the kit checks (" + kept + ")";
  const std::string step_words = step_comparison(d, start);
  // After a broken law: whether h is to blame as well.
  const auto about_h = [&] {
    if (beyond_critical(d))
      return " Besides, " + step_words + ": fix the forces first, then make h smaller.";
    if (d.forces_at_rest == ForcesAtRest::grow)
      return " The step is not the cause: " + step_words + ".";
    if (d.critical.source == LimitSource::not_computed)
      return d.forces_at_rest == ForcesAtRest::differ ? " (" + step_words + ".)" : std::string();
    return " The step is not the cause: " + step_words + ".";
  };

  if (!start_finite) {
    d.law = BrokenLaw::start_forces;
    d.time = start_time;
    d.equation = "(1.1)";
    words << "Why: the spring forces at the start (t = " << start_time
          << " s) are not finite numbers, before any step. ";
    int coincident = -1;
    for (std::size_t s = 0; s < start.springs.size() && coincident < 0; ++s) {
      const Spring& spring = start.springs[s];
      if ((particles.position.col(spring.p) - particles.position.col(spring.q)).norm() == 0.0)
        coincident = int(s);
    }
    if (coincident >= 0) {
      const Spring& s = start.springs[std::size_t(coincident)];
      words << "Spring " << coincident << " joins particles " << s.p << " and " << s.q
            << ", which start at the same place: the direction (r_p - r_q) / |r_p - r_q| in "
               "equation (1.1) divides by the length 0. Where the ends coincide, give the spring "
               "force 0.";
    } else {
      words << "Look for a division by a length or a distance that is 0 in equation (1.1), and "
               "for values used before they are set.";
    }
  } else if (!std::isnan(momentum_broke) && free_of_outside) {
    d.law = BrokenLaw::momentum;
    d.time = momentum_broke;
    d.amount = (momentum_end - p0).norm();
    d.equation = "(2.4)";
    words << "Why: the total momentum (the sum of m_i v_i) grew from " << significant(p0.norm())
          << " kg*m/s to " << significant(momentum_end.norm()) << " kg*m/s by t = " << end_time
          << " s (it first changed at t = " << momentum_broke
          << " s), but with no gravity, wind, push or pin acting, nothing outside the springs can "
             "change it: some spring pushes both of its ends the same way, or only one of them. "
             "Add F_pq to particle p and subtract it from particle q, equation (2.4): F_qp = "
             "-F_pq."
          << about_h();
  } else if (!std::isnan(momentum_broke) && gravity_only && std::isnan(gravity_wrong)) {
    // add_gravity added m_i g to every particle: the springs changed the momentum.
    d.law = BrokenLaw::momentum;
    d.time = momentum_broke;
    d.amount = deviation_end.norm();
    d.equation = "(2.4)";
    words << "Why: gravity alone changes the total momentum (the sum of m_i v_i) by t times the "
             "total mass times g, but by t = "
          << end_time << " s it had changed by " << vector_text(deviation_end)
          << " kg*m/s more than that (first at t = " << momentum_broke
          << " s), and gravity was added right (m_i g, equation (5.2)): some spring pushes both "
             "of its ends the same way, or only one of them. Add F_pq to particle p and subtract "
             "it from particle q, equation (2.4): F_qp = -F_pq."
          << about_h();
  } else if ((!std::isnan(momentum_broke) && gravity_only) || !std::isnan(gravity_wrong)) {
    d.law = BrokenLaw::gravity;
    d.equation = "(5.2)";
    words << "Why: ";
    if (!std::isnan(momentum_broke) && gravity_only) {
      d.time = momentum_broke;
      d.amount = deviation_end.norm();
      const double t = end_time - start_time;
      const Vec2 expected = t * total_mass * g;
      const Vec2 actual = momentum_end - p0;
      const double share = actual.dot(g) / std::max(expected.dot(g), 1e-300);
      words << "gravity alone changes the total momentum (the sum of m_i v_i) by t times the "
               "total mass times g, "
            << vector_text(expected) << " kg*m/s by t = " << end_time << " s, but it changed by "
            << vector_text(actual) << " kg*m/s (" << significant(share)
            << " times that; it first differed at t = " << momentum_broke << " s). ";
    }
    if (!std::isnan(gravity_wrong)) {
      if (std::isnan(d.time)) d.time = gravity_wrong;
      const int i = gravity_particle;
      const Vec2 expected = particles.mass[i] * g;
      if (d.amount == 0.0) d.amount = (gravity_added - expected).norm();
      words << "At t = " << gravity_wrong << " s add_gravity changed the force on particle " << i
            << " by " << vector_text(gravity_added)
            << " N, but its gravity is m_i g = " << vector_text(expected) << " N ("
            << significant(particles.mass[i]) << " kg times g)";
      if ((gravity_added - g).norm() <= 1e-9 * g.norm() && std::abs(particles.mass[i] - 1) > 1e-9)
        words << ": that is g without the mass";
      else if ((gravity_added + expected).norm() <= 1e-9 * expected.norm())
        words << ": that is gravity pointing the wrong way";
      else if ((gravity_added + gravity_spring - expected).norm() <=
               1e-9 * (expected.norm() + gravity_spring.norm()))
        words << ": the force was set to m_i g, and the spring forces already in it were lost";
      words << ". ";
    }
    words << "Gravity on particle i is m_i g, equation (5.2): F_i += m_i g, added to the forces "
             "already there."
          << about_h();
  } else if (!std::isnan(symmetry_broke)) {
    d.law = BrokenLaw::symmetry;
    d.time = symmetry_broke;
    d.amount = asymmetry_end;
    d.equation = spring_list_equations(p);
    words << "Why: the start is " << broken_mirror->name
          << " mirror symmetric, so the motion must stay its own mirror image, but at t = "
          << symmetry_broke << " s a particle was " << significant(asymmetry_at_break)
          << " m from the mirror image of its partner (" << significant(asymmetry_end)
          << " m by t = " << end_time << " s): ";
    const std::string spring = unmatched_spring(start.springs, *broken_mirror);
    if (!spring.empty())
      words << spring << ". ";
    else
      words << "the forces on mirrored particles differ. ";
    words << "A spring is missing, doubled or joins the wrong particles: check the index formula "
             "(2.1), index = i*cols + j, and the spring lists "
          << spring_list_equations(p) << "." << about_h();
  } else if (signs.exact && (signs.alpha < -0.5 || (signs.has_damping && signs.beta < -0.5) ||
                             (signs.has_damping && std::abs(signs.beta) < 0.05))) {
    d.law = BrokenLaw::energy;
    d.time = energy_doubled;
    const bool spring = signs.alpha < -0.5;
    const bool damper_missing = !spring && std::abs(signs.beta) < 0.05;
    d.amount = spring ? signs.alpha : signs.beta;
    d.equation = spring ? "(1.1)" : "(1.2)";
    words << "Why: ";
    if (damper_missing) {
      words << "the dampers give no force, so nothing removes energy: the damper force is "
               "F_pq = -b (v_p - v_q), equation (1.2), added with the spring force as in (2.3).";
    } else {
      words << "springs and dampers can only store or remove energy, but the "
            << (spring ? "spring" : "damper") << " forces point the wrong way (they are "
            << significant(d.amount) << " times what equation " << d.equation
            << " gives), so each step gives energy";
      if (!std::isnan(energy_doubled))
        words << ": the total energy rose from " << significant(start_energy) << " J to "
              << significant(end_energy) << " J by t = " << energy_time << " s";
      words << ". Check the sign in "
            << (spring ? "F_pq = -k (|r_p - r_q| - l0) (r_p - r_q) / |r_p - r_q|, equation (1.1)"
                       : "F_pq = -b (v_p - v_q), equation (1.2)")
            << ", and how (2.3) adds it.";
    }
    words << about_h();
  } else if (beyond_critical(d)) {
    d.law = BrokenLaw::step_size;
    d.time = start_time;
    d.amount = d.critical.step > 0 ? d.step / d.critical.step : infinity;
    words << "Why: " << step_words << ". ";
    if (!kept.empty()) {
      std::string sentence = kept_words + ". ";
      sentence[0] = char(std::toupper(sentence[0]));
      words << sentence;
    }
    if (d.critical.step > 0 && !drag_words(start, d.critical).empty())
      words << "Make h smaller than " << significant(d.critical.step)
            << " s, or wind.drag smaller or the mass larger: another integrator does not help.";
    else if (d.critical.step > 0)
      words << "Make h smaller than " << significant(d.critical.step)
            << " s, or choose an integrator with a larger critical step (springlab-run "
               "--stability lists them).";
    else
      words << "Choose another integrator (springlab-run --stability lists their critical "
               "steps).";
  } else if (budget_steps == 0 && n > budget.particles) {
    d.law = BrokenLaw::none;
    words << "Why: not replayed, the scene's " << n << " particles are more than the "
          << budget.particles << " the diagnosis replays; " << step_words << ".";
  } else if (d.forces_at_rest == ForcesAtRest::grow) {
    d.law = BrokenLaw::none;
    words << "Why: " << kept_words << "; " << step_words
          << ". Look at the spring and damper forces, (1.1) and (1.2), and how (2.3) adds them: "
             "forces that only store or remove energy make no motion grow.";
  } else if (d.critical.source == LimitSource::not_computed) {
    d.law = BrokenLaw::none;
    words << "Why: " << kept_words << "; " << step_words
          << ". If h is beyond the critical step, make h smaller or choose an integrator with a "
             "larger one; if not, look for a spring or damper force that points the wrong way, "
             "(1.1) and (1.2).";
  } else {
    const bool forces_right = signs.exact && std::abs(signs.alpha - 1.0) < 1e-6 &&
                              (!signs.has_damping || std::abs(signs.beta - 1.0) < 1e-6);
    const std::string forces_words =
        forces_right ? "the forces are right (on " + std::to_string(fit.samples) +
                           " evaluations they are exactly what (1.1), (1.2) and (2.3) give)"
        : signs.exact ? "the forces are " + significant(signs.alpha) + " times the spring forces" +
                            (signs.has_damping
                                 ? " plus " + significant(signs.beta) + " times the damper forces"
                                 : std::string()) +
                            " that (1.1), (1.2) and (2.3) give (on " + std::to_string(fit.samples) +
                            " evaluations)"
                      : "the forces kept what the kit checks";
    const std::string large_motion =
        "that critical step holds for small motions about rest, and here the springs start "
        "stretched or shrunk by up to " +
        significant(100.0 * start_strain) + " % of their rest length" +
        (std::isnan(strain_at_growth)
             ? std::string()
             : " (" + significant(100.0 * strain_at_growth) +
                   " % when the energy had doubled, t = " + significant(energy_doubled) + " s)") +
        ", beyond what the linear theory behind it describes";
    // Before the code under test is blamed, or h: the kit's reference on this scene at this h.
    const std::optional<bool> reference_too =
        reference_diverges(p, impl, start_time + double(steps) * p.step, budget);
    const std::string grown = std::isnan(energy_doubled)
                                  ? std::string()
                                  : "the total energy rose from " + significant(start_energy) +
                                        " J to " + significant(end_energy) +
                                        " J by t = " + significant(energy_time) + " s; ";
    if (reference_too && *reference_too) {
      d.law = BrokenLaw::step_size;
      d.time = std::isnan(energy_doubled) ? start_time : energy_doubled;
      d.amount = d.critical.step > 0 ? d.step / d.critical.step : infinity;
      words << "Why: " << grown
            << (impl.student_task == 0 ? "this is the kit's reference code, and "
                                       : "the kit's reference code diverges too on this scene at "
                                         "this h, so ")
            << "the step is the cause, not the code: " << step_words << ", but " << large_motion
            << ". Make h smaller (a half or less of the critical step), or start closer to rest.";
    } else if (reference_too) {  // the reference runs as long without diverging
      d.law = forces_right ? BrokenLaw::step_function : BrokenLaw::energy;
      d.time = std::isnan(energy_doubled) ? start_time : energy_doubled;
      d.equation = forces_right ? "" : "(2.3)";
      words << "Why: " << grown << "the kit's reference code runs this scene at this h for as "
            << "long without diverging, so your code is the cause, not h (" << step_words
            << "): " << forces_words << ". ";
      const long reference_springs = long(reference_springs_of(p));
      if (forces_right && reference_springs >= 0 && reference_springs != long(start.springs.size()))
        words << "Your code made " << start.springs.size() << " springs where the reference makes "
              << reference_springs << ": check the spring lists " << spring_list_equations(p)
              << ".";
      else if (forces_right && impl.student_task == 1 && p.integrator == "explicit-euler")
        words << euler_step_words;
      else if (forces_right && impl.student_task == 4 && p.integrator == "verlet")
        words << verlet_step_words;
      else if (!forces_right)
        words << "Check (1.1), (1.2) and how (2.3) adds them.";
    } else if (!std::isnan(energy_doubled) && !forces_right && signs.exact) {
      d.law = BrokenLaw::energy;
      d.time = energy_doubled;
      d.amount = end_energy - start_energy;
      d.equation = "(2.3)";
      words << "Why: " << grown << "although " << step_words << ", " << forces_words
            << ". Check (1.1), (1.2) and how (2.3) adds them.";
    } else {
      d.law = BrokenLaw::step_function;
      d.time = std::isnan(energy_doubled) ? start_time : energy_doubled;
      words << "Why: " << grown << (forces_right ? forces_words : kept_words) << "; " << step_words
            << ". ";
      if (impl.student_task == 1 && p.integrator == "explicit-euler")
        words << euler_step_words;
      else if (impl.student_task == 4 && p.integrator == "verlet")
        words << verlet_step_words;
      else
        words << "But " << large_motion << ": a smaller h helps.";
    }
  }
  if (budget_steps > 0 && !d.replayed_all && replayed < steps && d.law != BrokenLaw::start_forces)
    words << " (The diagnosis watched the first " << d.replayed << " s of the run only.)";
  if (budget_steps == 0 && n > budget.particles && d.law != BrokenLaw::none)
    words << " (The run was not replayed: its " << n << " particles are more than the "
          << budget.particles << " the diagnosis replays, so the laws of the forces were not "
          << "checked.)";
  d.words = words.str();
  return d;
}

}  // namespace springlab
