#include "gui/session.hpp"

#include "springlab/errors.hpp"
#include "springlab/memory_budget.hpp"
#include "springlab/scene.hpp"
#include "springlab/selection.hpp"
#include "springlab/stability.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <new>
#include <sstream>

namespace springlab::view {
namespace {

// A dense eigen-solve per change of a parameter: only small scenes get an estimate.
constexpr int critical_step_particle_limit = 100;

void push_capped(std::vector<float>& series, double value) {
  if (series.size() == History::capacity) series.erase(series.begin());
  // A runaway energy can exceed what a float holds; the plot shows it pinned at the top.
  const double largest = std::numeric_limits<float>::max();
  series.push_back(
      static_cast<float>(std::isnan(value) ? value : std::clamp(value, -largest, largest)));
}

// Every field as text: a cheap key that changes whenever the parameters do.
std::string fingerprint(const SceneParameters& p) {
  std::ostringstream out;
  out.precision(17);
  for_each_field(p, [&](const FieldInfo& info, const auto& value) {
    // Fields that text cannot show (none yet) still count by their key.
    if constexpr (requires { out << value; })
      if (info.key != "step") out << info.key << '=' << value << ';';
  });
  return out.str();
}

Problem problem_of(Problem::Kind kind, std::string headline, std::string detail) {
  Problem problem;
  problem.kind = kind;
  problem.headline = std::move(headline);
  problem.detail = std::move(detail);
  return problem;
}

// A std::bad_alloc the simulation has not already explained (it turns its own into
// InvalidParameter): the kit's words for it, with the scene's estimate and what is free now.
std::string out_of_memory(const SceneParameters& p) {
  try {
    throw_out_of_memory(p, "in the viewer");
  } catch (const InvalidParameter& error) {
    return error.what();
  }
}

}  // namespace

void History::add(double t, const Diagnostics& d) {
  push_capped(time, t);
  push_capped(kinetic, d.kinetic);
  push_capped(potential, d.all_potential());  // springs and gravity, as summaries say
  push_capped(total, d.total());
  push_capped(momentum_x, d.momentum.x());
  push_capped(momentum_y, d.momentum.y());
}

void History::clear() {
  for (auto* series : {&time, &kinetic, &potential, &total, &momentum_x, &momentum_y})
    series->clear();
}

Session::Session(const std::string& name_or_path) {
  load(name_or_path);
}

void Session::load(const std::string& name_or_path) {
  source_ = name_or_path;
  try {
    loaded_ = load_scene(name_or_path);
  } catch (const std::exception& error) {
    loaded_ = task_scene(1);  // something to edit; the problem says why it is not the file
    parameters_ = loaded_;
    primary_.reset();
    reference_.reset();
    ++builds_;  // no simulation now: what the panel took from the last one is gone
    problem_ = problem_of(Problem::Kind::invalid,
                          "The scene \"" + name_or_path + "\" cannot be loaded", error.what());
    running_ = false;
    return;
  }
  parameters_ = loaded_;
  reset();
}

void Session::reset() {
  toggled_pins_.clear();
  grabbed_ = -1;
  rebuild(false);
  running_ = primary_ != nullptr;
}

void Session::apply() {
  // A smaller grid keeps its particle sets inside it rather than refusing the new size: named
  // sets (top-row, …) follow the grid; a list that no longer fits becomes the last particle
  // (displaced, as in the task scenes) or none (pinned, pushed).
  const int particles = parameters_.rows * parameters_.cols;
  const auto fit = [&](const char* field, std::string& set, const std::string& fallback) {
    try {
      select_particles(field, set, parameters_.rows, parameters_.cols);
    } catch (const InvalidParameter&) {
      set = fallback;
    }
  };
  if (particles >= 2) {
    fit("displaced", parameters_.displaced, std::to_string(particles - 1));
    fit("pinned", parameters_.pinned, "none");
    fit("pushed", parameters_.pushed, "none");
  }
  rebuild(true);
}

void Session::set_code(Code code) {
  code_ = code;
  rebuild(true);
}

void Session::set_compare(Compare compare) {
  compare_ = reference_is_available() ? compare : Compare::off;
  rebuild(true);
}

void Session::set_running(bool running) {
  running_ = running && primary_ && problem_.kind == Problem::Kind::none;
}

std::unique_ptr<Simulation> Session::make(const Implementation& impl,
                                          const Simulation* previous) const {
  Scene scene = build_scene(parameters_, impl);
  Particles& particles = scene.particles;
  for (int i : toggled_pins_)
    if (i < particles.size()) particles.pinned[std::size_t(i)] = !particles.pinned[std::size_t(i)];
  if (previous) {
    particles.position = previous->particles().position;
    particles.velocity = previous->particles().velocity;
  }
  for (int i = 0; i < particles.size(); ++i)
    if (particles.pinned[std::size_t(i)]) particles.velocity.col(i).setZero();
  auto sim = std::make_unique<Simulation>(std::move(scene), impl);
  if (previous) sim->continue_from(*previous);
  return sim;
}

void Session::rebuild(bool keep_state) {
  ++builds_;
  // Carry the motion over only from a healthy run of the same particles.
  const bool keep = keep_state && primary_ && problem_.kind == Problem::Kind::none &&
                    primary_->parameters().rows == parameters_.rows &&
                    primary_->parameters().cols == parameters_.cols;
  const bool had_problem = problem_.kind != Problem::Kind::none;
  std::unique_ptr<Simulation> old_primary = std::move(primary_),
                              old_reference = std::move(reference_);
  problem_ = {};
  owed_steps_ = 0.0;
  if (!keep) {
    ++fresh_starts_;
    toggled_pins_.clear();
    history_.clear();
    grabbed_ = -1;
  }
  try {
    validate(parameters_);
    const Implementation& impl =
        code_ == Code::student ? student_code(parameters_.task) : reference_implementation();
    primary_ = make(impl, keep ? old_primary.get() : nullptr);
    if (compare_ != Compare::off && code_ == Code::student)
      reference_ = make(reference_implementation(),
                        keep ? (old_reference ? old_reference.get() : old_primary.get()) : nullptr);
    if (grabbed_ >= 0) {
      const int held = grabbed_;
      edit_each([&](Simulation& sim) { sim.set_pinned(held, true); });
    }
    primary_start_energy_ = primary_->diagnostics().total();
    if (reference_) reference_start_energy_ = reference_->diagnostics().total();
    if (history_.size() == 0) history_.add(time(), primary_->diagnostics());
  } catch (const InvalidParameter& error) {
    primary_.reset();
    reference_.reset();
    if (code_ == Code::student && error.field() == "task")
      problem_ = problem_of(
          Problem::Kind::invalid,
          "Scene \"" + parameters_.name + "\" belongs to no lab task: no student code to run",
          "Pick a task scene, or set task = N in the scene file. (" + std::string(error.what()) +
              ")");
    else
      report(error, "");
  } catch (const std::exception& error) {
    primary_.reset();
    reference_.reset();
    report(error, "");
  }
  if (!primary_) running_ = false;
  // A run stopped by a problem (not by the user) goes again once the problem is fixed.
  if (had_problem && primary_) running_ = true;
}

void Session::report(const std::exception& error, const std::string& whose) {
  running_ = false;
  if (const auto* diverged = dynamic_cast<const DivergenceError*>(&error)) {
    std::ostringstream headline;
    headline << whose << "The simulation diverged at t = " << diverged->time() << " s";
    // The banner says when and where on lines of their own; the detail keeps only the why.
    std::string why = error.what();
    const std::string where = diverged->quantity() + ": ";
    if (const auto at = why.find(where); at != std::string::npos) why.erase(0, at + where.size());
    // What ran away, then the kit's "Why: ..." (divergence.hpp), as one sentence each.
    if (!why.empty()) why[0] = char(std::toupper(static_cast<unsigned char>(why[0])));
    problem_ = problem_of(Problem::Kind::diverged, headline.str(), why);
    problem_.time = diverged->time();
    problem_.particle = diverged->particle();
    problem_.quantity = diverged->quantity();
  } else if (const auto* missing = dynamic_cast<const NotImplemented*>(&error)) {
    const std::string task = std::to_string(missing->task());
    problem_ =
        problem_of(Problem::Kind::not_implemented,
                   "Task " + task + " is not implemented yet \u2014 see handout section " + task,
                   error.what());
  } else if (dynamic_cast<const InvalidParameter*>(&error)) {
    problem_ =
        problem_of(Problem::Kind::invalid, whose + "A parameter is out of range", error.what());
  } else if (dynamic_cast<const std::bad_alloc*>(&error)) {
    problem_ =
        problem_of(Problem::Kind::invalid, whose + "Out of memory", out_of_memory(parameters_));
  } else {
    problem_ =
        problem_of(Problem::Kind::failed, whose + "The code under test failed", error.what());
  }
}

double Session::time() const {
  return primary_ ? primary_->time() : 0.0;
}

long Session::frame(double seconds) {
  const long steps = steps_due(seconds);
  advance(steps);
  return steps;
}

long Session::steps_due(double seconds, long most) {
  dropped_steps_ = 0;
  if (!running_ || !primary_) return 0;
  long steps = pacing_.steps_per_frame;
  if (pacing_.real_time) {
    const double lasted = std::clamp(seconds, 0.0, pacing_.longest_frame);
    owed_steps_ += pacing_.real_time_factor * lasted / parameters_.step;
    // A tiny h can owe more steps than a frame may take (or a long holds): the rest is dropped.
    const double due = std::floor(owed_steps_ + 1e-9);  // 3 × (1/3) is one whole step
    steps = long(std::min({due, double(pacing_.max_steps_per_frame), double(most)}));
    owed_steps_ = due > double(steps) ? 0.0 : owed_steps_ - double(steps);
    dropped_steps_ = long(std::min(due - double(steps), 1e18));  // a tiny h owes ~1e300
  }
  return std::max(steps, 0L);
}

void Session::single_step() {
  if (primary_ && problem_.kind == Problem::Kind::none) advance(1);
}

void Session::advance(long steps) {
  for (long n = 0; n < steps && problem_.kind == Problem::Kind::none; ++n) {
    try {
      primary_->step();
    } catch (const std::exception& error) {
      report(error, code_ == Code::student && reference_ ? "Your code: " : "");
      // The reference, run beside it, is one step behind: it takes the same step, and what it
      // did is said, unless the diagnosis (which runs the reference itself when the forces kept
      // every law) has said it already. Only what was run is said: a reference that took this
      // step may still diverge later.
      if (reference_ && problem_.kind == Problem::Kind::diverged && reference_is_available() &&
          problem_.detail.find("reference code") == std::string::npos)
        problem_.detail += reference_takes_the_step();
    }
    if (!reference_ || problem_.kind != Problem::Kind::none) continue;
    try {
      reference_->step();
    } catch (const std::exception& error) {
      report(error, "The reference: ");
    }
  }
  if (steps > 0 && primary_) history_.add(time(), primary_->diagnostics());
}

std::string Session::reference_takes_the_step() {
  try {
    reference_->step();
  } catch (const DivergenceError&) {
    return " The reference code, run beside yours, diverges at this same step too: at this h the "
           "step itself makes the motion grow, whatever the code.";
  } catch (const std::exception&) {
    return "";  // the reference's own failure is not this problem's
  }
  return " The reference code, run beside yours, took this same step without diverging.";
}

double Session::largest_difference() const {
  if (!primary_ || !reference_) return 0.0;
  const Vectors& a = primary_->particles().position;
  const Vectors& b = reference_->particles().position;
  return (a - b).colwise().norm().maxCoeff();
}

std::optional<Comparison> Session::comparison() const {
  // Nothing to compare before a step (a task not written yet never takes one): "ends 0 m from
  // the reference's run" would read as agreement.
  if (!primary_ || !reference_ || primary_->steps_taken() == 0 ||
      primary_->steps_taken() != reference_->steps_taken())
    return std::nullopt;
  return compare_runs(parameters_, record_of(*primary_, primary_start_energy_),
                      record_of(*reference_, reference_start_energy_));
}

std::optional<double> Session::critical_step() {
  const std::string key = fingerprint(parameters_);
  if (key == critical_key_) return critical_;
  critical_key_ = key;
  critical_.reset();
  critical_estimate_ = false;
  try {
    validate(parameters_);
    if (parameters_.rows * parameters_.cols <= critical_step_particle_limit) {
      critical_ = springlab::critical_step(
          linearise_at_rest(parameters_, reference_implementation()), parameters_.integrator);
      critical_note_.clear();
      return critical_;
    }
    // Larger scenes: no eigen-solve, an estimate from the bound on ω_max (stability.hpp).
    const StabilityReport report = stability_report(parameters_, reference_implementation(), 0);
    for (const StabilityReport::Limit& limit : report.limits)
      if (limit.integrator == parameters_.integrator &&
          limit.critical.source != LimitSource::not_computed)
        critical_ = limit.critical.step;
    critical_estimate_ = critical_.has_value() && std::isfinite(*critical_) && *critical_ > 0.0;
    critical_note_ = critical_ ? ""
                               : "not estimated for this method above " +
                                     std::to_string(critical_step_particle_limit) + " particles";
  } catch (const std::exception& error) {
    critical_note_ = std::string("no estimate: ") + error.what();
  }
  return critical_;
}

template <class Edit>
void Session::edit_each(Edit&& edit) {
  for (Simulation* sim : {primary_.get(), reference_.get()})
    if (sim) edit(*sim);
}

void Session::grab(int particle) {
  if (!primary_ || particle < 0 || particle >= primary_->particles().size()) return;
  release();
  grabbed_ = particle;
  grabbed_was_pinned_ = pinned(particle);
  edit_each([&](Simulation& sim) { sim.set_pinned(particle, true); });
}

void Session::drag_to(const Vec2& position) {
  if (grabbed_ < 0) return;
  edit_each([&](Simulation& sim) { sim.set_particle(grabbed_, position, Vec2::Zero()); });
}

void Session::release() {
  if (grabbed_ < 0) return;
  const int held = grabbed_;
  grabbed_ = -1;
  if (!grabbed_was_pinned_) edit_each([&](Simulation& sim) { sim.set_pinned(held, false); });
}

void Session::toggle_pin(int particle) {
  if (!primary_ || particle < 0 || particle >= primary_->particles().size()) return;
  const bool pin = !pinned(particle);
  if (!toggled_pins_.erase(particle)) toggled_pins_.insert(particle);
  if (particle == grabbed_) {
    grabbed_was_pinned_ = pin;
    return;
  }
  edit_each([&](Simulation& sim) { sim.set_pinned(particle, pin); });
}

void Session::push(int particle, const Vec2& velocity_change) {
  if (!primary_ || particle < 0 || particle >= primary_->particles().size()) return;
  edit_each([&](Simulation& sim) {
    const Particles& p = sim.particles();
    sim.set_particle(particle, p.position.col(particle),
                     p.velocity.col(particle) + velocity_change);
  });
}

bool Session::pinned(int particle) const {
  if (!primary_ || particle < 0 || particle >= primary_->particles().size()) return false;
  if (particle == grabbed_) return grabbed_was_pinned_;
  return primary_->particles().pinned[std::size_t(particle)];
}

}  // namespace springlab::view
