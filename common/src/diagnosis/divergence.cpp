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
namespace {

// The evidence of a replay: one watch for each law the forces must keep, each with what it saw.

// Newton's third law through the total momentum: with nothing outside the springs acting it
// keeps its start value, and with gravity alone it changes by t times the total mass times g.
struct MomentumWatch {
  bool free_of_outside = false;  // no gravity, wind, push or pin
  bool gravity_only = false;     // gravity, and no wind, push or pin
  double total_mass = 0.0;       // kg
  Vec2 g = Vec2::Zero();         // m/s², zero without gravity
  Vec2 p0 = Vec2::Zero();        // kg·m/s, the start's
  double scale = 0.0;            // kg·m/s, the largest Σ m_i |v_i| so far
  double broke = not_a_number;   // s, when it first left what the law allows
  Vec2 end = Vec2::Zero(), deviation_end = Vec2::Zero();  // kg·m/s, at the replay's last step

  MomentumWatch(const SceneParameters& p, const Particles& particles, double start_time) {
    const bool pinned =
        std::find(particles.pinned.begin(), particles.pinned.end(), true) != particles.pinned.end();
    const bool pushed = p.push_duration > start_time && !p.push.isZero() && p.pushed != "none";
    free_of_outside = !p.gravity.enabled && !p.wind.enabled && !pushed && !pinned;
    gravity_only = p.gravity.enabled && !p.wind.enabled && !pushed && !pinned;
    total_mass = particles.mass.sum();
    g = p.gravity.enabled ? p.gravity.acceleration : Vec2::Zero();
    p0 = linear_momentum(particles.mass, particles.velocity);
    scale = (particles.mass.transpose() * particles.velocity.colwise().norm().transpose()).value();
    end = p0;
  }

  void observe(const Particles& now, double t, double start_time, const SceneParameters& p) {
    scale =
        std::max(scale, (now.mass.transpose() * now.velocity.colwise().norm().transpose()).value());
    const Vec2 momentum = linear_momentum(now.mass, now.velocity);
    if (!free_of_outside && !gravity_only) return;
    const Vec2 deviation = momentum - p0 - (t - start_time) * total_mass * g;
    double tolerance = 1e-6 * std::max(scale, 1e-3 * total_mass * p.spacing);
    if (gravity_only) tolerance += 2 * p.step * total_mass * g.norm();
    if (std::isnan(broke) && deviation.norm() > tolerance) broke = t;
    end = momentum;
    deviation_end = deviation;
  }
};

// Gravity as (5.2): what add_gravity added to the spring forces, against m_i g.
struct GravityWatch {
  Eigen::VectorXd mass;         // kg, the particles'
  Vec2 g = Vec2::Zero();        // m/s², zero without gravity
  Vectors spring_forces;        // N, the last forces before gravity
  double wrong = not_a_number;  // s, when add_gravity first added other than m_i g
  int particle = -1;            // the particle it was wrong on
  Vec2 added = Vec2::Zero(), spring = Vec2::Zero();  // N, what it added, the springs' force there

  void after_springs(const Vectors& f) { spring_forces = f; }
  void after_gravity(const Vectors& f, double time) {
    if (!std::isnan(wrong) || spring_forces.cols() != f.cols()) return;
    const Vectors gravity = f - spring_forces;
    for (Eigen::Index i = 0; i < f.cols(); ++i) {
      const Vec2 expected = mass[i] * g;
      const Vec2 error = gravity.col(i) - expected;
      if (!(error.norm() <= 1e-9 * (expected.norm() + spring_forces.col(i).norm()))) {
        wrong = time;
        particle = int(i);
        added = gravity.col(i);
        spring = spring_forces.col(i);
        break;
      }
    }
  }
};

// The mirror symmetry of the start, which the motion must keep (a spring missing, doubled or
// misplaced breaks it).
struct SymmetryWatch {
  std::vector<Mirror> mirrors;       // those the start is symmetric under
  Vectors r0;                        // m, the start's positions
  bool window = true;                // whether no particle has yet moved a spacing from the grid
  int broken = -1;                   // the mirror broken first, -1 for none
  double broke = not_a_number;       // s, when
  double at_break = 0.0, end = 0.0;  // m, the mismatch then and at the replay's last step

  // Symmetry is judged until a particle first moves a grid spacing from where the whole grid
  // moved: a motion that large may break it on its own (a symmetric oscillation can pump an
  // antisymmetric one out of rounding), and one that runs away amplifies the rounding of
  // mirrored sums without bound.
  void observe(const Vectors& position, double t, double spacing) {
    if (mirrors.empty()) return;
    const Vectors moved = position - r0;
    const Vec2 mean = moved.rowwise().mean();
    window = window && (moved.colwise() - mean).colwise().norm().maxCoeff() <= spacing;
    for (std::size_t i = 0; i < mirrors.size(); ++i) {
      if (broken < 0 && window) {
        const double mismatch = mirrors[i].mismatch(position);
        if (mismatch > 1e-6 * spacing) {
          broke = t;
          broken = int(i);
          at_break = mismatch;
        }
      }
      if (int(i) == broken) end = mirrors[i].mismatch(position);
    }
  }
};

// The total energy, every few steps: when it had doubled, and how far the springs were
// stretched then.
struct EnergyWatch {
  double start = 0.0, end = 0.0, reference = 0.0;  // J
  double time = 0.0;                               // s, when `end` was measured
  double doubled = not_a_number;                   // s, when it first passed twice the reference
  double start_strain = 0.0;                       // the largest |L - l0| / l0 at the start
  double strain_at_growth = not_a_number;          // ... when it had doubled

  void observe(const Simulation& replay, const std::vector<Spring>& springs) {
    end = replay.diagnostics().total();
    time = replay.time();
    if (std::isnan(doubled) && end > 2 * reference) {
      doubled = time;
      strain_at_growth = strain_of(springs, replay.particles().position);
    }
  }
};

// The steps of the run the budget lets the replay take, 0 for none.
long replay_budget(int particles, long steps, const DiagnosisBudget& budget) {
  if (particles > budget.particles || steps <= 0) return 0;
  return std::min(steps, long(std::max(1.0, budget.particle_steps / std::max(particles, 1))));
}

// Everything the replay saw, each watch set on the start before any step.
struct Evidence {
  long budget_steps = 0;     // the steps the budget allows, 0: not replayed
  long replayed = 0;         // the steps tried
  double end_time = 0.0;     // s, the time of the last one
  bool start_finite = true;  // whether the first forces were finite numbers
  MomentumWatch momentum;
  GravityWatch gravity;
  SymmetryWatch symmetry;
  EnergyWatch energy;
  SignFit fit;  // the directions of the spring and damper forces, (1.1) and (1.2)

  Evidence(const Scene& start, double start_time, long steps, const DiagnosisBudget& budget)
      : budget_steps(replay_budget(start.particles.size(), steps, budget)),
        end_time(start_time),
        momentum(start.parameters, start.particles, start_time) {
    gravity.mass = start.particles.mass;
    gravity.g = momentum.g;
    symmetry.mirrors = symmetric_mirrors(start);
    symmetry.r0 = start.particles.position;
    energy.time = start_time;
    energy.start_strain = strain_of(start.springs, start.particles.position);
  }
};

// The replay's look at the forces: whether they start finite, their directions against the
// kit's springs and dampers (stage 0), what add_gravity added (stage 1).
struct ForceLook {
  Evidence& e;
  const Simulation& replay;
  SpringsApart apart;
  Vectors kit_spring, kit_damper;  // N
  long evaluations = 0;

  ForceLook(Evidence& evidence, const Simulation& run, const Scene& start)
      : e(evidence),
        replay(run),
        apart(start.springs, start.parameters.rows, start.parameters.cols) {}

  void operator()(int stage, const Vectors& r, const Vectors& v, const Vectors& f) {
    if (stage == 1) {
      e.gravity.after_gravity(f, replay.time());
      return;
    }
    e.gravity.after_springs(f);
    if (++evaluations == 1) e.start_finite = f.allFinite();
    if (e.fit.samples >= 400 || !f.allFinite() || !r.allFinite() || !v.allFinite()) return;
    apart.forces(r, v, kit_spring, kit_damper);
    e.fit.add(f, kit_spring, kit_damper);
  }
};

// Replays the run's first steps (as many as the budget allows) with the same code, each law
// watched.
Evidence replay_run(const Scene& start, const Implementation& impl, double start_time, long steps,
                    const DiagnosisBudget& budget) {
  Evidence e(start, start_time, steps, budget);
  if (e.budget_steps == 0) return e;
  try {
    DivergenceLimits quiet;
    quiet.energy_growth = infinity;
    quiet.energy_check_interval = INT_MAX;
    quiet.diagnose = false;
    Simulation replay(Scene(start), impl, quiet);
    detail::ReplayAccess::start_at(replay, start_time);
    ForceLook look(e, replay, start);
    detail::ReplayAccess::watch_forces(
        replay, [&look](int stage, const Vectors& r, const Vectors& v, const Vectors& f) {
          look(stage, r, v, f);
        });
    e.energy.start = replay.diagnostics().total();
    e.energy.reference = replay.reference_energy();
    const int check_every = 8;
    for (long k = 0; k < e.budget_steps; ++k) {
      ++e.replayed;  // counted when tried: the run's last step may be the one that fails
      replay.step();
      const double t = replay.time();
      e.end_time = t;
      e.momentum.observe(replay.particles(), t, start_time, start.parameters);
      e.symmetry.observe(replay.particles().position, t, start.parameters.spacing);
      if (k % check_every == check_every - 1 || k + 1 == e.budget_steps)
        e.energy.observe(replay, start.springs);
    }
  } catch (const std::exception&) {
    // The replay diverged too (it ends where the run did) or its code failed: what it saw so far
    // is the evidence.
  }
  return e;
}

// What the checks read: the run, the replay's evidence, and the words every check may use.
struct Findings {
  const Scene& start;
  const Implementation& impl;
  double start_time;  // s
  long steps;
  const DiagnosisBudget& budget;
  const Evidence& e;
  SignFit::Result signs;   // the forces as multiples of the kit's springs and dampers
  std::string kept;        // the laws the replay checked and the forces kept, "" for none
  std::string kept_words;  // ... in a clause
  std::string step_words;  // h against the critical step (step_comparison)

  // After a broken law: whether h is to blame as well.
  std::string about_h(const Diagnosis& d) const {
    if (beyond_critical(d))
      return " Besides, " + step_words + ": fix the forces first, then make h smaller.";
    if (d.forces_at_rest == ForcesAtRest::grow)
      return " The step is not the cause: " + step_words + ".";
    if (d.critical.source == LimitSource::not_computed)
      return d.forces_at_rest == ForcesAtRest::differ ? " (" + step_words + ".)" : std::string();
    return " The step is not the cause: " + step_words + ".";
  }
  // Whether the scene was too large to replay.
  bool not_replayed() const {
    return e.budget_steps == 0 && start.particles.size() > budget.particles;
  }
};

// What the replay could check on this scene, in words: "" when it checked nothing.
std::string laws_kept(const Evidence& e) {
  if (e.replayed == 0) return "";
  std::vector<std::string> laws;
  if (e.momentum.free_of_outside) laws.push_back("the total momentum, (2.4)");
  if (e.momentum.gravity_only) laws.push_back("the momentum gravity gives, (5.2)");
  if (!e.symmetry.mirrors.empty()) laws.push_back("the mirror symmetry of the start");
  if (e.fit.samples > 0)
    laws.push_back("the directions of the spring and damper forces, (1.1) and (1.2)");
  std::string kept;
  for (std::size_t i = 0; i < laws.size(); ++i)
    kept += (i == 0 ? "" : i + 1 == laws.size() ? " and " : ", ") + laws[i];
  return kept;
}

// The checks, in the order the diagnosis tries them: each one law (or, last, the step against the
// code), true when it is the verdict, with its evidence in d and its sentences in words.
using Check = bool (*)(const Findings& f, Diagnosis& d, std::ostream& words);

// The spring forces are not finite numbers before any step: a spring whose ends coincide (1.1).
bool start_forces_not_finite(const Findings& f, Diagnosis& d, std::ostream& words) {
  if (f.e.start_finite) return false;
  const std::vector<Spring>& springs = f.start.springs;
  const Vectors& r = f.start.particles.position;
  d.law = BrokenLaw::start_forces;
  d.time = f.start_time;
  d.equation = "(1.1)";
  words << "Why: the spring forces at the start (t = " << f.start_time
        << " s) are not finite numbers, before any step. ";
  int coincident = -1;
  for (std::size_t s = 0; s < springs.size() && coincident < 0; ++s)
    if ((r.col(springs[s].p) - r.col(springs[s].q)).norm() == 0.0) coincident = int(s);
  if (coincident >= 0) {
    const Spring& s = springs[std::size_t(coincident)];
    words << "Spring " << coincident << " joins particles " << s.p << " and " << s.q
          << ", which start at the same place: the direction (r_p - r_q) / |r_p - r_q| in "
             "equation (1.1) divides by the length 0. Where the ends coincide, give the spring "
             "force 0.";
  } else {
    words << "Look for a division by a length or a distance that is 0 in equation (1.1), and "
             "for values used before they are set.";
  }
  return true;
}

// Nothing outside the springs acts, yet the total momentum changed: F_qp = -F_pq broken (2.4).
// The momentum law (2.4) broken at `time` by `amount`, and the one fix both checks below give.
constexpr const char* spring_pushes_one_way =
    "some spring pushes both of its ends the same way, or only one of them. Add F_pq to particle "
    "p and subtract it from particle q, equation (2.4): F_qp = -F_pq.";

void momentum_broken(Diagnosis& d, double time, double amount) {
  d.law = BrokenLaw::momentum;
  d.time = time;
  d.amount = amount;
  d.equation = "(2.4)";
}

bool momentum_not_kept(const Findings& f, Diagnosis& d, std::ostream& words) {
  const MomentumWatch& m = f.e.momentum;
  if (std::isnan(m.broke) || !m.free_of_outside) return false;
  momentum_broken(d, m.broke, (m.end - m.p0).norm());
  words << "Why: the total momentum (the sum of m_i v_i) grew from " << significant(m.p0.norm())
        << " kg*m/s to " << significant(m.end.norm()) << " kg*m/s by t = " << f.e.end_time
        << " s (it first changed at t = " << m.broke
        << " s), but with no gravity, wind, push or pin acting, nothing outside the springs can "
           "change it: "
        << spring_pushes_one_way << f.about_h(d);
  return true;
}

// Gravity alone acts and add_gravity added m_i g to every particle, yet the momentum changed by
// more than gravity gives: the springs changed it (2.4).
bool momentum_beyond_gravity(const Findings& f, Diagnosis& d, std::ostream& words) {
  const MomentumWatch& m = f.e.momentum;
  if (std::isnan(m.broke) || !m.gravity_only || !std::isnan(f.e.gravity.wrong)) return false;
  momentum_broken(d, m.broke, m.deviation_end.norm());
  words << "Why: gravity alone changes the total momentum (the sum of m_i v_i) by t times the "
           "total mass times g, but by t = "
        << f.e.end_time << " s it had changed by " << vector_text(m.deviation_end)
        << " kg*m/s more than that (first at t = " << m.broke
        << " s), and gravity was added right (m_i g, equation (5.2)): " << spring_pushes_one_way
        << f.about_h(d);
  return true;
}

// The momentum gravity gives against the change the replay saw, in a sentence.
void gravity_momentum_words(const Findings& f, Diagnosis& d, std::ostream& words) {
  const MomentumWatch& m = f.e.momentum;
  d.time = m.broke;
  d.amount = m.deviation_end.norm();
  const double t = f.e.end_time - f.start_time;
  const Vec2 expected = t * m.total_mass * m.g;
  const Vec2 actual = m.end - m.p0;
  const double share = actual.dot(m.g) / std::max(expected.dot(m.g), 1e-300);
  words << "gravity alone changes the total momentum (the sum of m_i v_i) by t times the "
           "total mass times g, "
        << vector_text(expected) << " kg*m/s by t = " << f.e.end_time << " s, but it changed by "
        << vector_text(actual) << " kg*m/s (" << significant(share)
        << " times that; it first differed at t = " << m.broke << " s). ";
}

// What add_gravity added to one particle against m_i g, and the likely mistake, in a sentence.
void gravity_added_words(const Findings& f, Diagnosis& d, std::ostream& words) {
  const GravityWatch& gw = f.e.gravity;
  const Vec2& g = gw.g;
  if (std::isnan(d.time)) d.time = gw.wrong;
  const int i = gw.particle;
  const double mass = f.start.particles.mass[i];
  const Vec2 expected = mass * g;
  if (d.amount == 0.0) d.amount = (gw.added - expected).norm();
  words << "At t = " << gw.wrong << " s add_gravity changed the force on particle " << i << " by "
        << vector_text(gw.added) << " N, but its gravity is m_i g = " << vector_text(expected)
        << " N (" << significant(mass) << " kg times g)";
  if ((gw.added - g).norm() <= 1e-9 * g.norm() && std::abs(mass - 1) > 1e-9)
    words << ": that is g without the mass";
  else if ((gw.added + expected).norm() <= 1e-9 * expected.norm())
    words << ": that is gravity pointing the wrong way";
  else if ((gw.added + gw.spring - expected).norm() <= 1e-9 * (expected.norm() + gw.spring.norm()))
    words << ": the force was set to m_i g, and the spring forces already in it were lost";
  words << ". ";
}

// Gravity is not m_i g added to the forces (5.2): the momentum it gives is wrong, or add_gravity
// was seen adding something else.
bool gravity_not_m_g(const Findings& f, Diagnosis& d, std::ostream& words) {
  const MomentumWatch& m = f.e.momentum;
  const bool momentum_wrong = !std::isnan(m.broke) && m.gravity_only;
  if (!momentum_wrong && std::isnan(f.e.gravity.wrong)) return false;
  d.law = BrokenLaw::gravity;
  d.equation = "(5.2)";
  words << "Why: ";
  if (momentum_wrong) gravity_momentum_words(f, d, words);
  if (!std::isnan(f.e.gravity.wrong)) gravity_added_words(f, d, words);
  words << "Gravity on particle i is m_i g, equation (5.2): F_i += m_i g, added to the forces "
           "already there."
        << f.about_h(d);
  return true;
}

// A mirror-symmetric start whose motion stopped being its own mirror image: a spring missing,
// doubled or misplaced (2.1) and the spring lists.
bool symmetry_broken(const Findings& f, Diagnosis& d, std::ostream& words) {
  const SymmetryWatch& s = f.e.symmetry;
  if (std::isnan(s.broke)) return false;
  const Mirror& mirror = s.mirrors[std::size_t(s.broken)];
  const SceneParameters& p = f.start.parameters;
  d.law = BrokenLaw::symmetry;
  d.time = s.broke;
  d.amount = s.end;
  d.equation = spring_list_equations(p);
  words << "Why: the start is " << mirror.name
        << " mirror symmetric, so the motion must stay its own mirror image, but at t = " << s.broke
        << " s a particle was " << significant(s.at_break)
        << " m from the mirror image of its partner (" << significant(s.end)
        << " m by t = " << f.e.end_time << " s): ";
  const std::string spring = unmatched_spring(f.start.springs, mirror);
  if (!spring.empty())
    words << spring << ". ";
  else
    words << "the forces on mirrored particles differ. ";
  words << "A spring is missing, doubled or joins the wrong particles: check the index formula "
           "(2.1), index = i*cols + j, and the spring lists "
        << spring_list_equations(p) << "." << f.about_h(d);
  return true;
}

// The spring or damper forces point the wrong way, or the dampers give none: energy is given,
// or nothing removes it (1.1), (1.2).
bool force_signs_give_energy(const Findings& f, Diagnosis& d, std::ostream& words) {
  const SignFit::Result& signs = f.signs;
  if (!(signs.exact && (signs.alpha < -0.5 || (signs.has_damping && signs.beta < -0.5) ||
                        (signs.has_damping && std::abs(signs.beta) < 0.05))))
    return false;
  const EnergyWatch& energy = f.e.energy;
  d.law = BrokenLaw::energy;
  d.time = energy.doubled;
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
    if (!std::isnan(energy.doubled))
      words << ": the total energy rose from " << significant(energy.start) << " J to "
            << significant(energy.end) << " J by t = " << energy.time << " s";
    words << ". Check the sign in "
          << (spring ? "F_pq = -k (|r_p - r_q| - l0) (r_p - r_q) / |r_p - r_q|, equation (1.1)"
                     : "F_pq = -b (v_p - v_q), equation (1.2)")
          << ", and how (2.3) adds it.";
  }
  words << f.about_h(d);
  return true;
}

// Every law kept, and h beyond the critical step of the forces that ran: h is the cause.
bool step_beyond_critical(const Findings& f, Diagnosis& d, std::ostream& words) {
  if (!beyond_critical(d)) return false;
  d.law = BrokenLaw::step_size;
  d.time = f.start_time;
  d.amount = d.critical.step > 0 ? d.step / d.critical.step : infinity;
  words << "Why: " << f.step_words << ". ";
  if (!f.kept.empty()) {
    std::string sentence = f.kept_words + ". ";
    sentence[0] = char(std::toupper(sentence[0]));
    words << sentence;
  }
  if (d.critical.step > 0 && !drag_words(f.start, d.critical).empty())
    words << "Make h smaller than " << significant(d.critical.step)
          << " s, or wind.drag smaller or the mass larger: another integrator does not help.";
  else if (d.critical.step > 0)
    words << "Make h smaller than " << significant(d.critical.step)
          << " s, or choose an integrator with a larger critical step (springlab-run "
             "--stability lists them).";
  else
    words << "Choose another integrator (springlab-run --stability lists their critical "
             "steps).";
  return true;
}

// The scene is beyond the replay's budget: only the step limit can be said.
bool scene_not_replayed(const Findings& f, Diagnosis& d, std::ostream& words) {
  if (!f.not_replayed()) return false;
  d.law = BrokenLaw::none;
  words << "Why: not replayed, the scene's " << f.start.particles.size()
        << " particles are more than the " << f.budget.particles << " the diagnosis replays; "
        << f.step_words << ".";
  return true;
}

// The code's own forces, measured about rest, make motion grow in exact time: no h helps.
bool own_forces_grow(const Findings& f, Diagnosis& d, std::ostream& words) {
  if (d.forces_at_rest != ForcesAtRest::grow) return false;
  d.law = BrokenLaw::none;
  words << "Why: " << f.kept_words << "; " << f.step_words
        << ". Look at the spring and damper forces, (1.1) and (1.2), and how (2.3) adds them: "
           "forces that only store or remove energy make no motion grow.";
  return true;
}

// No critical step is known to compare h with: both causes are named.
bool limit_unknown(const Findings& f, Diagnosis& d, std::ostream& words) {
  if (d.critical.source != LimitSource::not_computed) return false;
  d.law = BrokenLaw::none;
  words << "Why: " << f.kept_words << "; " << f.step_words
        << ". If h is beyond the critical step, make h smaller or choose an integrator with a "
           "larger one; if not, look for a spring or damper force that points the wrong way, "
           "(1.1) and (1.2).";
  return true;
}

// Below the critical step with every law kept: what the forces are against (1.1), (1.2) and
// (2.3), the motion's size against the linear theory, and the energy's growth, in words.
struct BelowLimit {
  bool forces_right = false;  // exactly the kit's springs and dampers
  std::string forces_words, large_motion, grown;

  explicit BelowLimit(const Findings& f) {
    const SignFit::Result& signs = f.signs;
    const EnergyWatch& energy = f.e.energy;
    const int samples = f.e.fit.samples;
    forces_right = signs.exact && std::abs(signs.alpha - 1.0) < 1e-6 &&
                   (!signs.has_damping || std::abs(signs.beta - 1.0) < 1e-6);
    forces_words =
        forces_right ? "the forces are right (on " + std::to_string(samples) +
                           " evaluations they are exactly what (1.1), (1.2) and (2.3) give)"
        : signs.exact ? "the forces are " + significant(signs.alpha) + " times the spring forces" +
                            (signs.has_damping
                                 ? " plus " + significant(signs.beta) + " times the damper forces"
                                 : std::string()) +
                            " that (1.1), (1.2) and (2.3) give (on " + std::to_string(samples) +
                            " evaluations)"
                      : "the forces kept what the kit checks";
    large_motion =
        "that critical step holds for small motions about rest, and here the springs start "
        "stretched or shrunk by up to " +
        significant(100.0 * energy.start_strain) + " % of their rest length" +
        (std::isnan(energy.strain_at_growth)
             ? std::string()
             : " (" + significant(100.0 * energy.strain_at_growth) +
                   " % when the energy had doubled, t = " + significant(energy.doubled) + " s)") +
        ", beyond what the linear theory behind it describes";
    grown = std::isnan(energy.doubled)
                ? std::string()
                : "the total energy rose from " + significant(energy.start) + " J to " +
                      significant(energy.end) + " J by t = " + significant(energy.time) + " s; ";
  }
};

// Where only the code's step can be the cause, what to look at for its task, "" if none.
const char* step_advice(const Findings& f) {
  const SceneParameters& p = f.start.parameters;
  if (f.impl.student_task == 1 && p.integrator == "explicit-euler") return euler_step_words;
  if (f.impl.student_task == 4 && p.integrator == "verlet") return verlet_step_words;
  return nullptr;
}

// The kit's reference diverges too: h is the cause, though below the small-motion limit.
void reference_diverges_too(const Findings& f, const BelowLimit& b, Diagnosis& d,
                            std::ostream& words) {
  const double doubled = f.e.energy.doubled;
  d.law = BrokenLaw::step_size;
  d.time = std::isnan(doubled) ? f.start_time : doubled;
  d.amount = d.critical.step > 0 ? d.step / d.critical.step : infinity;
  words << "Why: " << b.grown
        << (f.impl.student_task == 0 ? "this is the kit's reference code, and "
                                     : "the kit's reference code diverges too on this scene at "
                                       "this h, so ")
        << "the step is the cause, not the code: " << f.step_words << ", but " << b.large_motion
        << ". Make h smaller (a half or less of the critical step), or start closer to rest.";
}

// The kit's reference runs as long without diverging: the code under test is the cause.
void reference_runs(const Findings& f, const BelowLimit& b, Diagnosis& d, std::ostream& words) {
  const SceneParameters& p = f.start.parameters;
  const double doubled = f.e.energy.doubled;
  d.law = b.forces_right ? BrokenLaw::step_function : BrokenLaw::energy;
  d.time = std::isnan(doubled) ? f.start_time : doubled;
  d.equation = b.forces_right ? "" : "(2.3)";
  words << "Why: " << b.grown << "the kit's reference code runs this scene at this h for as "
        << "long without diverging, so your code is the cause, not h (" << f.step_words
        << "): " << b.forces_words << ". ";
  const long reference_springs = long(reference_springs_of(p));
  const std::size_t springs = f.start.springs.size();
  if (b.forces_right && reference_springs >= 0 && reference_springs != long(springs))
    words << "Your code made " << springs << " springs where the reference makes "
          << reference_springs << ": check the spring lists " << spring_list_equations(p) << ".";
  else if (b.forces_right && step_advice(f))
    words << step_advice(f);
  else if (!b.forces_right)
    words << "Check (1.1), (1.2) and how (2.3) adds them.";
}

// No reference to compare with, and the energy grew with forces that are not (1.1) and (1.2)'s.
bool energy_grew_with_wrong_forces(const Findings& f, const BelowLimit& b, Diagnosis& d,
                                   std::ostream& words) {
  const EnergyWatch& energy = f.e.energy;
  if (std::isnan(energy.doubled) || b.forces_right || !f.signs.exact) return false;
  d.law = BrokenLaw::energy;
  d.time = energy.doubled;
  d.amount = energy.end - energy.start;
  d.equation = "(2.3)";
  words << "Why: " << b.grown << "although " << f.step_words << ", " << b.forces_words
        << ". Check (1.1), (1.2) and how (2.3) adds them.";
  return true;
}

// No reference to compare with and nothing wrong seen: the step function, or the motion's size.
void step_function_or_large_motion(const Findings& f, const BelowLimit& b, Diagnosis& d,
                                   std::ostream& words) {
  const double doubled = f.e.energy.doubled;
  d.law = BrokenLaw::step_function;
  d.time = std::isnan(doubled) ? f.start_time : doubled;
  words << "Why: " << b.grown << (b.forces_right ? b.forces_words : f.kept_words) << "; "
        << f.step_words << ". ";
  if (step_advice(f))
    words << step_advice(f);
  else
    words << "But " << b.large_motion << ": a smaller h helps.";
}

// Below the critical step with every law kept (the last check, always a verdict): before the code
// under test is blamed, or h, the kit's reference on this scene at this h.
bool below_critical(const Findings& f, Diagnosis& d, std::ostream& words) {
  const BelowLimit b(f);
  const SceneParameters& p = f.start.parameters;
  const std::optional<bool> reference_too =
      reference_diverges(p, f.impl, f.start_time + double(f.steps) * p.step, f.budget);
  if (reference_too && *reference_too)
    reference_diverges_too(f, b, d, words);
  else if (reference_too)
    reference_runs(f, b, d, words);
  else if (!energy_grew_with_wrong_forces(f, b, d, words))
    step_function_or_large_motion(f, b, d, words);
  return true;
}

constexpr Check checks[] = {start_forces_not_finite, momentum_not_kept,  momentum_beyond_gravity,
                            gravity_not_m_g,         symmetry_broken,    force_signs_give_energy,
                            step_beyond_critical,    scene_not_replayed, own_forces_grow,
                            limit_unknown,           below_critical};

// How much of the run the diagnosis watched, where not all of it.
void replay_notes(const Findings& f, const Diagnosis& d, std::ostream& words) {
  const Evidence& e = f.e;
  if (e.budget_steps > 0 && !d.replayed_all && e.replayed < f.steps &&
      d.law != BrokenLaw::start_forces)
    words << " (The diagnosis watched the first " << d.replayed << " s of the run only.)";
  if (f.not_replayed() && d.law != BrokenLaw::none)
    words << " (The run was not replayed: its " << f.start.particles.size()
          << " particles are more than the " << f.budget.particles
          << " the diagnosis replays, so the laws of the forces were not checked.)";
}

}  // namespace

Diagnosis diagnose_divergence(const Scene& start, const Implementation& impl, double start_time,
                              long steps, const DiagnosisBudget& budget) {
  Diagnosis d;
  d.step = start.parameters.step;
  d.critical = scene_critical_step(start, budget, &d.growth);
  limit_of_forces_that_ran(d, start, impl, budget);

  const Evidence e = replay_run(start, impl, start_time, steps, budget);
  d.replayed = e.end_time - start_time;
  d.replayed_all = e.budget_steps > 0 && e.replayed == steps;

  const std::string kept = laws_kept(e);
  const Findings f{.start = start,
                   .impl = impl,
                   .start_time = start_time,
                   .steps = steps,
                   .budget = budget,
                   .e = e,
                   .signs = e.fit.solve(),
                   .kept = kept,
                   .kept_words = kept.empty()
                                     ? "the kit could check no law of the forces here"
                                     : "the forces kept what the kit checks (" + kept + ")",
                   .step_words = step_comparison(d, start)};
  std::ostringstream words;
  for (const Check check : checks)
    if (check(f, d, words)) break;
  replay_notes(f, d, words);
  d.words = words.str();
  return d;
}

}  // namespace springlab
