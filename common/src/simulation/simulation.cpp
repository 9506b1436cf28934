#include "springlab/simulation.hpp"

#include "springlab/divergence.hpp"
#include "springlab/errors.hpp"
#include "springlab/memory_budget.hpp"
#include "springlab/parallel.hpp"
#include "springlab/selection.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <new>
#include <sstream>
#include <string>

namespace springlab {
namespace {

// Energy of every spring stretched by 10 % of its rest length: the scale of a moderate motion.
double moderate_energy(const std::vector<Spring>& springs) {
  double energy = 0.0;
  for (const Spring& s : springs)
    energy += 0.5 * s.k * std::pow(0.1 * s.rest_length, 2);
  return energy;
}

// The scale of the energy the wind and the push can give (see DivergenceLimits).
double external_energy(const Particles& particles, const SceneParameters& p, int pushed) {
  const double total_mass = particles.mass.sum();
  double energy = 0.0;
  if (p.wind.enabled) energy += 0.5 * total_mass * std::pow(1.5 * p.wind.speed, 2);
  const double lightest = particles.mass.minCoeff();
  if (pushed > 0) energy += pushed * std::pow(p.push.norm() * p.push_duration, 2) / (2 * lightest);
  return energy;
}

}  // namespace

// A grid that passed the memory guard can still exhaust memory (other programs, a poor
// estimate): that becomes a clear error, not "std::bad_alloc".
Simulation::Simulation(const SceneParameters& p, const Implementation& impl,
                       DivergenceLimits limits) try
    : Simulation(build_scene(p, impl), impl, limits) {
} catch (const std::bad_alloc&) {
  throw_out_of_memory(p, "while building the scene");
}

Simulation::Simulation(Scene scene, const Implementation& impl, DivergenceLimits limits)
    : scene_(std::move(scene)),
      impl_(&impl),
      integrator_(make_integrator(scene_.parameters.integrator, impl, scene_.parameters.xpbd)),
      acceleration_function_([this](const Vectors& r, const Vectors& v) -> const Vectors& {
        return acceleration(r, v);
      }),
      external_function_([this](const Vectors& r, const Vectors& v) -> const Vectors& {
        return external_acceleration(r, v);
      }),
      limits_(limits) {
  validate(scene_);
  const Particles& particles = scene_.particles;
  const SceneParameters& p = scene_.parameters;
  inverse_mass_ = particles.mass.cwiseInverse();
  if (particles.size() > 0 && particles.mass.maxCoeff() == particles.mass.minCoeff())
    same_mass_ = particles.mass[0];
  list_pins();
  start_position_ = particles.position;
  if (p.wind.enabled) wind_.emplace(p.wind);
  pushed_ = select_particles("pushed", p.pushed, p.rows, p.cols);
  if (p.push_duration == 0.0 || p.push.isZero()) pushed_.clear();
  const Diagnostics start = diagnostics();
  // The floor, every particle moving one spacing per second, matters for scenes without springs.
  const double floor = 0.5 * particles.mass.sum() * p.spacing * p.spacing;
  reference_energy_ = std::max({start.total(), moderate_energy(scene_.springs), floor}) +
                      external_energy(particles, p, int(pushed_.size()));
  if (is_kit_model(impl) && particles.size() == p.rows * p.cols)
    grid_ = GridForces::of(scene_.springs, p.rows, p.cols);
  // Verlet's iterations ask for a(r, v) again at the same r with a new v.
  if (grid_) grid_->remember_springs(p.integrator == "verlet");
  restart_stretch();
  check_divergence(true);
}

const Vectors& Simulation::acceleration(const Vectors& r, const Vectors& v) {
  ++evaluations_;
  const SceneParameters& p = scene_.parameters;
  const Particles& particles = scene_.particles;
  const bool pushing = time() < p.push_duration && !pushed_.empty();
  if (fast_forces() && !force_watch_) {
    // Springs, gravity, wind, masses and pins in one pass per thread; a push after.
    GridFinish finish;
    if (p.gravity.enabled) {
      finish.gravity = &p.gravity.acceleration;
      finish.mass = &particles.mass;
    }
    if (wind_) {  // sampled at the step's start time, as below
      finish.wind = &*wind_;
      finish.time = time();
    }
    finish.same_mass = same_mass_;
    if (!pushing) {
      finish.inverse_mass = &inverse_mass_;
      finish.acceleration = &acceleration_;
      if (!pinned_list_.empty()) finish.pinned = &pinned_list_;
    }
    grid_->compute(r, v, force_, finish);
    if (finish.acceleration) return acceleration_;
  } else {
    // A replay watches each stage. Replaying a fast-path run, it takes its springs from the fast
    // path too: the steps below add in the same order with the same operations as that path's
    // pass, so the replay follows the run it explains to the bit.
    if (fast_forces()) {
      grid_->compute(r, v, force_);
    } else {
      force_.setZero(2, r.cols());
      impl_->accumulate_spring_forces(scene_.springs, r, v, force_);
    }
    if (force_watch_) force_watch_(0, r, v, force_);
    if (p.gravity.enabled) {
      impl_->add_gravity(particles.mass, p.gravity.acceleration, force_);
      if (force_watch_) force_watch_(1, r, v, force_);
    }
    // The wind is sampled at the start of the step: its gusts change over seconds, not steps.
    if (wind_ && fast_forces()) {
      grid_->add_wind(*wind_, time(), r, v, force_);
    } else if (wind_) {
      wind_->begin_pass();
      impl_->add_wind(*wind_, time(), r, v, force_);
    }
  }
  if (pushing)
    for (int i : pushed_)
      force_.col(i) += p.push;
  acceleration_.noalias() = force_ * inverse_mass_.asDiagonal();
  if (!pinned_list_.empty()) impl_->hold_pinned(particles.pinned, acceleration_);
  return acceleration_;
}

const Vectors& Simulation::external_acceleration(const Vectors& r, const Vectors& v) {
  ++external_evaluations_;
  const SceneParameters& p = scene_.parameters;
  const Particles& particles = scene_.particles;
  external_force_.setZero(2, r.cols());
  if (p.gravity.enabled)
    impl_->add_gravity(particles.mass, p.gravity.acceleration, external_force_);
  if (wind_ && fast_forces()) {
    grid_->add_wind(*wind_, time(), r, v, external_force_);
  } else if (wind_) {
    wind_->begin_pass();
    impl_->add_wind(*wind_, time(), r, v, external_force_);
  }
  if (time() < p.push_duration)
    for (int i : pushed_)
      external_force_.col(i) += p.push;
  external_.noalias() = external_force_ * inverse_mass_.asDiagonal();
  if (!pinned_list_.empty()) impl_->hold_pinned(particles.pinned, external_);
  return external_;
}

Diagnostics Simulation::diagnostics() const {
  const SceneParameters& p = scene_.parameters;
  const Vec2 g = p.gravity.enabled ? p.gravity.acceleration : Vec2::Zero();
  if (fast_forces())
    return diagnose(scene_.particles, grid_->spring_energy(scene_.particles.position), g,
                    start_position_);
  return diagnose(scene_.particles, scene_.springs, g, start_position_);
}

void Simulation::step() {
  Particles& particles = scene_.particles;
  try {
    const Model model{acceleration_function_, scene_.springs, particles.mass, particles.pinned,
                      &external_function_};
    integrator_->step(model, scene_.parameters.step, particles.position, particles.velocity);
    ++steps_;
    ++stretch_steps_;
    check_divergence(steps_ % limits_.energy_check_interval == 0);
  } catch (const std::bad_alloc&) {
    std::ostringstream when;
    when << "at t = " << time() << " s";
    throw_out_of_memory(scene_.parameters, when.str());
  } catch (const StepFailed& failure) {
    // Name the fastest particle: where a step that cannot settle is most likely to go wrong.
    Eigen::Index fastest = 0;
    if (particles.velocity.allFinite())
      particles.velocity.colwise().squaredNorm().maxCoeff(&fastest);
    std::string why = failure.what();
    if (const std::string facts = settling_facts(); !facts.empty())
      why += (why.ends_with('.') ? " " : ". ") + facts;
    else if (const std::string words = diagnosis(); !words.empty())
      why += (why.ends_with('.') ? " " : ". ") + words;
    throw DivergenceError(time(), int(fastest), "the " + std::string(integrator_->name()) + " step",
                          why);
  }
}

std::string Simulation::settling_facts() const {
  // A student's Verlet step that gave up iterating (4.1)-(4.2): each pass shrinks the velocity's
  // error by h c/2 at most, c the largest damping rate per unit mass, bounded by the Gershgorin
  // row sums of M^-1 C (2 Σ b / m_i over a particle's springs, and the wind's drag). Far below 1,
  // 100 passes must settle, so the dampers are not why this one did not.
  if (impl_->student_task != 4 || integrator_->name() != "verlet") return "";
  const Particles& particles = scene_.particles;
  Eigen::VectorXd damping = Eigen::VectorXd::Zero(particles.size());
  for (const Spring& s : scene_.springs) {
    damping[s.p] += 2 * s.b;
    damping[s.q] += 2 * s.b;
  }
  const WindParameters& wind = scene_.parameters.wind;
  if (wind.enabled) damping.array() += wind.drag;
  const double c = (damping.array() / particles.mass.array()).maxCoeff();
  const double q = scene_.parameters.step * c / 2;
  if (!(q < 0.5)) return "";
  std::ostringstream words;
  words << "The dampers are not the cause: here h c/2 is at most " << std::setprecision(3) << q
        << " (c, the largest damping rate per unit mass, from the scene's b, m and wind), so each "
           "pass of (4.1)-(4.2) shrinks the velocity's error at least that much and 100 passes "
           "settle it. Look at what verlet_step's loop hands velocity_settled(...) (two "
           "successive estimates of (4.2)'s v_n, then the positions r and h for the scale) and at "
           "whether each "
           "pass updates its estimate: handout section 4.";
  return words.str();
}

void Simulation::check() const {
  check_divergence(true);
}

void Simulation::advance(long steps) {
  for (long i = 0; i < steps; ++i)
    step();
}

void Simulation::check_index(int i) const {
  const int n = scene_.particles.size();
  if (i < 0 || i >= n)
    throw InvalidParameter("particle", std::to_string(i),
                           "0 <= particle <= " + std::to_string(n - 1));
}

void Simulation::set_particle(int i, const Vec2& position, const Vec2& velocity) {
  check_index(i);
  Particles& particles = scene_.particles;
  particles.position.col(i) = position;
  particles.velocity.col(i) = particles.pinned[i] ? Vec2::Zero() : velocity;
  integrator_->restart();
  restart_stretch();
  // A hand that drags a particle far adds energy no step made: not a divergence.
  reference_energy_ = std::max(reference_energy_, diagnostics().total());
}

void Simulation::list_pins() {
  const std::vector<bool>& pinned = scene_.particles.pinned;
  pinned_list_.clear();
  for (std::size_t i = 0; i < pinned.size(); ++i)
    if (pinned[i]) pinned_list_.push_back(int(i));
}

void Simulation::set_pinned(int i, bool pinned) {
  check_index(i);
  Particles& particles = scene_.particles;
  particles.pinned[i] = pinned;  // the model's hold_pinned (5.5) now holds it
  list_pins();
  if (pinned) particles.velocity.col(i).setZero();
  integrator_->restart();
  restart_stretch();
}

void Simulation::continue_from(const Simulation& previous) {
  if (previous.particles().size() != particles().size())
    throw InvalidParameter(
        "continue_from", std::to_string(previous.particles().size()) + " particles",
        "a run of the same " + std::to_string(particles().size()) + " particles");
  start_time_ = previous.time();
  steps_ = 0;
  start_position_ = previous.start_position_;
  reference_energy_ = std::max(reference_energy_, previous.reference_energy_);
  restart_stretch();
}

void Simulation::restart_stretch() {
  stretch_time_ = time();
  stretch_steps_ = 0;
  // Huge scenes keep no copy: their diagnosis rests on the step limit alone.
  if (limits_.diagnose && scene_.particles.size() <= DiagnosisBudget{}.particles)
    stretch_start_ = scene_.particles;
  else
    stretch_start_.reset();
}

std::string Simulation::diagnosis() const {
  if (!limits_.diagnose) return "";
  if (!stretch_start_) return diagnose_divergence(scene_, *impl_, stretch_time_, 0).words;
  const Scene start{scene_.parameters, *stretch_start_, scene_.springs};
  return diagnose_divergence(start, *impl_, stretch_time_, stretch_steps_).words;
}

void Simulation::check_divergence(bool check_energy) const {
  const Particles& particles = scene_.particles;
  const double non_finite_blocks = sum_blocks(particles.size(), [&](long begin, long end) {
    const long count = end - begin;
    return particles.position.middleCols(begin, count).allFinite() &&
                   particles.velocity.middleCols(begin, count).allFinite()
               ? 0.0
               : 1.0;
  });
  if (non_finite_blocks > 0) {
    const auto [particle, quantity] = first_non_finite(particles);
    std::ostringstream why;
    why << "it is no longer a finite number.";
    if (const std::string words = diagnosis(); !words.empty()) why << ' ' << words;
    throw DivergenceError(time(), particle, quantity, why.str());
  }
  const double limit = limits_.energy_growth * reference_energy_;
  // The kinetic energy alone can pass the limit without a runaway (a long fall under gravity
  // turns potential energy into it): then the total decides. (A NaN or infinity fails `<=`.)
  if (!check_energy && kinetic_energy(particles.mass, particles.velocity) <= limit) return;
  const Diagnostics d = diagnostics();
  const double energy = d.total();
  // The total is a sum of large terms when a long fall has traded gravity's energy for kinetic:
  // what rounding leaves of it (relative 1e-16 a step, over millions of steps) is no runaway. A
  // runaway makes the total grow with the kinetic energy, far beyond this allowance.
  const double rounding = 1e-6 * (d.kinetic + std::abs(d.potential) + std::abs(d.gravitational));
  if (energy <= limit + rounding) return;
  Eigen::Index fastest = 0;
  particles.velocity.colwise().squaredNorm().maxCoeff(&fastest);
  std::ostringstream why;
  why << "the total energy " << energy << " J is more than " << limits_.energy_growth
      << " times its reference " << reference_energy_ << " J (runaway growth); particle " << fastest
      << " is the fastest at " << particles.velocity.col(fastest).norm() << " m/s.";
  if (const std::string words = diagnosis(); !words.empty()) why << ' ' << words;
  throw DivergenceError(time(), int(fastest), "total energy", why.str());
}

}  // namespace springlab
