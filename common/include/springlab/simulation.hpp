// A running scene: the model (forces → accelerations), an integrator and a divergence watch,
// advanced by a fixed step. Used by the runner, the viewer and the tests alike.
#pragma once

#include "springlab/diagnostics.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/implementation.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"
#include "springlab/wind.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string_view>

namespace springlab {

/// When a run counts as diverged (besides any NaN or infinity, which always does).
struct DivergenceLimits {
  /// The total energy may not exceed this many times the reference energy: the larger of the
  /// energy at t = 0, the energy of every spring stretched by 10 % of its rest length and the
  /// kinetic energy of every particle moving one grid spacing per second, plus
  /// what the wind and the push can give (every free particle at 1.5 times the wind speed, and
  /// moving at the speed the push gives it alone). Springs and gravity store energy and dampers
  /// remove it, so a stable step never comes near; an unstable one passes it within a few
  /// hundred steps of reaching visible amplitudes.
  double energy_growth = 1e4;
  /// Steps between checks of the total energy (springs and gravity included, a pass over the
  /// springs). After every step the state's finiteness and its kinetic energy (one pass over the
  /// particles, no force evaluation) are checked, and the total too whenever the kinetic energy
  /// alone passes the limit: so no step that ran away is ever seen by a caller (a CSV row, the
  /// viewer), since a runaway step makes the velocities grow with everything else.
  int energy_check_interval = 8;
  /// Whether a divergence report says why, from physics (divergence.hpp): the run keeps its
  /// state at the start (or at the last set_particle, set_pinned or continue_from) and, when it
  /// diverges, replays itself from there with the same code, watching the laws the forces must
  /// keep, and compares h with the method's critical step on the scene.
  bool diagnose = true;
};

namespace detail {
struct ReplayAccess;
}

class Simulation {
 public:
  /// Builds the scene of p with impl's functions and p.integrator.
  Simulation(const SceneParameters& p, const Implementation& impl, DivergenceLimits limits = {});
  /// Runs a scene built (and perhaps changed) elsewhere: its parameters say h and the integrator.
  Simulation(Scene scene, const Implementation& impl, DivergenceLimits limits = {});
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// One step of h = parameters().step. Throws DivergenceError (when, which particle, what) if
  /// the state stops being finite or the energy runs away; its message ends with the diagnosis
  /// of diagnose_divergence (divergence.hpp) when limits.diagnose.
  void step();
  void advance(long steps);
  /// The full divergence check (finiteness and total energy) on the current state; step() checks
  /// the total energy only every energy_check_interval steps (the kinetic energy every step), so
  /// call this at the end of a run.
  void check() const;

  /// The model the integrator sees: a_i = F_i / m_i with the spring and damper forces of every
  /// spring (impl.accumulate_spring_forces), then the forces the scene enables: gravity
  /// (impl.add_gravity), wind at the step's start time (impl.add_wind), the push; then
  /// impl.hold_pinned when any particle is pinned. A scene pays only for what it enables.
  /// With the kit's own model (is_kit_model(impl)) on a grid of whole spring families the springs,
  /// gravity, wind, masses and pins take the fast path (grid_forces.hpp), equal up to rounding.
  const Vectors& acceleration(const Vectors& r, const Vectors& v);

  /// The forces besides the springs and dampers, divided by the mass: gravity, the wind at the
  /// step's start time and the push, held at zero for pinned particles, m/s². What xpbd takes
  /// explicitly (Model::external); not a force evaluation (external_evaluations counts it).
  const Vectors& external_acceleration(const Vectors& r, const Vectors& v);
  long external_evaluations() const { return external_evaluations_; }

  /// Whether acceleration() takes the fast path; set_fast_forces(false) turns it off (to compare
  /// the two), true turns it back on where the scene allows it.
  bool fast_forces() const { return grid_.has_value() && use_grid_; }
  void set_fast_forces(bool on) { use_grid_ = on; }

  /// s: the time it started from (continue_from) plus the steps taken.
  double time() const { return start_time_ + double(steps_) * scene_.parameters.step; }
  long steps_taken() const { return steps_; }
  long force_evaluations() const { return evaluations_; }
  const Scene& scene() const { return scene_; }
  const Particles& particles() const { return scene_.particles; }
  const SceneParameters& parameters() const { return scene_.parameters; }
  const Implementation& implementation() const { return *impl_; }
  Integrator& integrator() { return *integrator_; }
  const Integrator& integrator() const { return *integrator_; }
  /// Energies (gravity's measured from the start positions) and momenta of the current state.
  Diagnostics diagnostics() const;
  double reference_energy() const { return reference_energy_; }  ///< J, see DivergenceLimits

  /// Sets particle i's position (m) and velocity (m/s) from outside, as the viewer does for a
  /// dragged or pushed particle; a pinned particle keeps zero velocity. Restarts the integrator,
  /// whose memory of earlier steps no longer matches the state. Throws InvalidParameter for an
  /// index outside the particles.
  void set_particle(int i, const Vec2& position, const Vec2& velocity);
  /// Pins (its acceleration and velocity held at zero) or frees particle i; restarts the
  /// integrator. Throws InvalidParameter for an index outside the particles.
  void set_pinned(int i, bool pinned);
  /// Goes on from `previous`, a run of as many particles whose state this one started from (the
  /// viewer rebuilds a run when a parameter changes): its time, the start positions gravity's
  /// energy is measured from, and its reference energy. So a change mid-run neither replays the
  /// wind's gusts and the push nor re-bases the divergence watch.
  void continue_from(const Simulation& previous);

 private:
  void list_pins();  // pinned_list_ from the particles' flags
  friend struct detail::ReplayAccess;
  /// What a replay sees of the forces: after the springs (stage 0) and after gravity (stage 1).
  using ForceWatch =
      std::function<void(int stage, const Vectors& r, const Vectors& v, const Vectors& force)>;

  void check_divergence(bool check_energy) const;
  void check_index(int i) const;
  /// The state a diagnosis replays from: the current one, from now on.
  void restart_stretch();
  /// diagnose_divergence's words on the steps since restart_stretch, or "" without diagnose.
  std::string diagnosis() const;
  std::string settling_facts() const;  // why a student's Verlet step that gave up is not h's

  Scene scene_;
  const Implementation* impl_;
  std::unique_ptr<Integrator> integrator_;
  AccelerationFunction acceleration_function_;
  AccelerationFunction external_function_;
  DivergenceLimits limits_;
  double reference_energy_ = 0.0;
  double start_time_ = 0.0;  // s
  long steps_ = 0;
  long evaluations_ = 0;
  long external_evaluations_ = 0;
  Eigen::VectorXd inverse_mass_;  // 1/m_i
  double same_mass_ = 0.0;  // every particle's mass when they are all equal (the lab's), else 0
  std::vector<int> pinned_list_;   // the pinned particles, ascending (list_pins)
  std::optional<WindField> wind_;  // when the scene has wind
  std::vector<int> pushed_;        // the particles the push acts on
  Vectors start_position_;         // where gravity's potential energy is zero
  Vectors force_, acceleration_;
  Vectors external_force_, external_;       // external_acceleration's
  std::optional<Particles> stretch_start_;  // the state a diagnosis replays from (small scenes)
  double stretch_time_ = 0.0;               // s, its time
  long stretch_steps_ = 0;                  // steps since then
  ForceWatch force_watch_;                  // a replay's look at the forces
  std::optional<GridForces> grid_;          // the fast path, where the scene allows it
  bool use_grid_ = true;
};

}  // namespace springlab
