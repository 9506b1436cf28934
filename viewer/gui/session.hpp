// What the viewer runs, with no graphics: the scene's parameters, the simulation of the chosen
// code (and the reference beside it when comparing), stepping by a fixed h, and what went wrong.
// The window only draws a Session and forwards the user's edits to it, so tests can drive it too.
#pragma once

#include "springlab/comparison.hpp"
#include "springlab/implementation.hpp"
#include "springlab/parameters.hpp"
#include "springlab/simulation.hpp"

#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace springlab::view {

enum class Code { reference, student };
enum class Compare { off, overlay, side_by_side };

/// Why the simulation is not running, in words for the banner.
struct Problem {
  enum class Kind { none, diverged, not_implemented, invalid, failed };
  Kind kind = Kind::none;
  std::string headline;  ///< one line, e.g. "Task 2 is not implemented yet — see handout section 2"
  std::string detail;    ///< the error's own words
  double time = 0.0;     ///< s, when it diverged
  int particle = -1;     ///< where it diverged, -1 for the whole scene
  std::string quantity;  ///< what diverged, e.g. "velocity.x"
};

/// The last samples of what the plots show, one sample per frame.
struct History {
  static constexpr std::size_t capacity = 600;  // 10 s at 60 frames per second
  std::vector<float> time, kinetic, potential, total, momentum_x, momentum_y;
  void add(double t, const Diagnostics& d);
  void clear();
  std::size_t size() const { return time.size(); }
};

/// How far the simulation advances per frame: a whole number of fixed steps h, never a step of
/// the frame's length. In real-time mode the count follows from the real-time factor and the
/// frame's duration, carrying the fraction to the next frame (1.67 steps a frame at h = 0.01 s
/// and 60 frames/s); otherwise it is steps_per_frame.
struct Pacing {
  bool real_time = true;
  double real_time_factor = 1.0;       ///< simulated seconds per wall-clock second
  int steps_per_frame = 1;             ///< used when real_time is off
  double frame_interval = 1.0 / 60.0;  ///< s, the frame rate the viewer aims at
  double longest_frame = 0.1;          ///< s: a stall (a window drag) is not caught up beyond it
  long max_steps_per_frame = 20000;    ///< keeps the window responsive
};

class Session {
 public:
  /// Loads scene `name_or_path` (task1 … or a scene file); a scene that cannot be loaded
  /// becomes the Problem shown in the window.
  explicit Session(const std::string& name_or_path = "task4");

  void load(const std::string& name_or_path);
  const std::string& source() const { return source_; }

  /// The parameters the sliders edit; call apply() after changing them.
  SceneParameters& parameters() { return parameters_; }
  const SceneParameters& parameters() const { return parameters_; }
  /// The parameters as loaded: the sliders' ranges are set from them.
  const SceneParameters& loaded_parameters() const { return loaded_; }
  /// Rebuilds the simulation from parameters(), keeping positions, velocities and pins when the
  /// particle count is unchanged (a new k, h or integrator takes effect mid-motion).
  void apply();
  /// Back to the scene's start with the current parameters.
  void reset();

  /// Where the student's code of task N comes from: student_implementation (tests put the
  /// reference here to compare two complete runs).
  const Implementation& (*student_code)(int task) = &student_implementation;

  Code code() const { return code_; }
  void set_code(Code code);
  Compare compare() const { return compare_; }
  void set_compare(Compare compare);
  /// The task whose student code runs (the scene's task), 0 when the scene has none.
  int task() const { return parameters_.task; }

  bool running() const { return running_; }
  /// Runs only while there is a simulation and no problem (a diverged run stays paused).
  void set_running(bool running);
  Pacing& pacing() { return pacing_; }
  const Pacing& pacing() const { return pacing_; }
  /// Advances a frame that lasted `seconds` (the headless runs and tests pass exactly 1/60 s,
  /// so they repeat to the bit) when running; returns the steps taken.
  long frame(double seconds);
  /// frame() in two halves, for a stepping thread: the steps due for a frame that lasted
  /// `seconds` (0 when not running), at most `most` of them in real-time mode (the rest are
  /// dropped, see dropped_steps), counted as taken; then advance() takes them.
  long steps_due(double seconds, long most = std::numeric_limits<long>::max());
  /// The steps the last steps_due dropped because a frame may not take so many.
  long dropped_steps() const { return dropped_steps_; }
  /// Takes `steps` steps h (fewer when the run stops on a problem) and records the history.
  void advance(long steps);
  /// One step h, also when paused.
  void single_step();

  /// The chosen code's simulation; nullptr when it could not be built.
  const Simulation* primary() const { return primary_.get(); }
  /// The reference running beside the student's code; nullptr unless comparing.
  const Simulation* reference() const { return reference_.get(); }
  const Problem& problem() const { return problem_; }
  /// Counts the rebuilds that started the scene afresh (new scene, reset, new grid): the view
  /// fits itself to each.
  int fresh_starts() const { return fresh_starts_; }
  /// Counts every rebuild of the simulations, fresh or carrying the motion over.
  int builds() const { return builds_; }
  double time() const;  ///< s since the last reset
  const History& history() const { return history_; }
  /// The largest distance between a particle of the student's run and the same particle of the
  /// reference's, m; 0 unless comparing.
  double largest_difference() const;
  /// The student's run against the reference's beside it since the last rebuild
  /// (comparison.hpp): figures and a remark; empty unless comparing.
  std::optional<Comparison> comparison() const;

  /// The critical step of the chosen integrator on this scene at rest, s (0: unstable at every
  /// h, infinity: stable at every h); empty when not estimated (large scene, unknown method).
  std::optional<double> critical_step();
  std::string critical_step_note() const { return critical_note_; }
  /// Whether critical_step() is an estimate from the bound on ω_max (scenes above 100
  /// particles, no eigen-solve) rather than the limit itself; for Verlet a step that is
  /// certainly stable, below the exact 2/ω_max.
  bool critical_step_is_estimate() const { return critical_estimate_; }

  // The user's hands on the particles; each applies to every running simulation.
  void grab(int particle);  ///< holds it still (pinned) until release()
  void drag_to(const Vec2& position);
  void release();
  int grabbed() const { return grabbed_; }
  void toggle_pin(int particle);
  void push(int particle, const Vec2& velocity_change);
  bool pinned(int particle) const;

 private:
  std::unique_ptr<Simulation> make(const Implementation& impl, const Simulation* previous) const;
  void rebuild(bool keep_state);
  void report(const std::exception& error, const std::string& whose);
  /// After the code under test diverged: the reference, one step behind, takes the same step;
  /// what it did, as a sentence for the divergence's detail ("" if it failed otherwise).
  std::string reference_takes_the_step();
  template <class Edit>
  void edit_each(Edit&& edit);

  std::string source_;
  SceneParameters loaded_, parameters_;
  Code code_ = Code::reference;
  Compare compare_ = Compare::off;
  bool running_ = true;
  Pacing pacing_;
  double owed_steps_ = 0.0;  // the fraction of a step carried to the next frame
  long dropped_steps_ = 0;
  std::unique_ptr<Simulation> primary_, reference_;
  double primary_start_energy_ = 0.0, reference_start_energy_ = 0.0;  // J, at the last rebuild
  Problem problem_;
  History history_;
  std::set<int> toggled_pins_;  // pins the user changed, kept across rebuilds
  int grabbed_ = -1;
  int fresh_starts_ = 0, builds_ = 0;
  bool grabbed_was_pinned_ = false;
  std::string critical_key_, critical_note_;
  std::optional<double> critical_;
  bool critical_estimate_ = false;
};

}  // namespace springlab::view
