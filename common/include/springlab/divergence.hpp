// Why a run diverged, from physics: the laws the forces must keep and the step limit of the
// method on the scene. Simulation replays a diverged run with the same code and the same
// inputs (deterministic, so the grader's two processes see the same calls), watching after every
// step what the student's forces must keep:
//   - the total momentum Σ m_i v_i, unchanged when no gravity, wind, push or pin acts (Newton's
//     third law, equation (2.4)), and changed by exactly t·Σ m_i·g by gravity alone (5.2);
//   - what add_gravity adds to each particle's force: m_i g (5.2), with pins and wind too;
//   - the mirror image of a mirror-symmetric start (left-right or up-down about the grid's centre
//     line) stays its mirror image (the spring lists (2.1), (2.2), (3.1), (5.1));
//   - finite forces at the start state (a spring whose ends coincide, equation (1.1));
//   - the spring and damper forces point the way (1.1) and (1.2) say: the kit compares them
//     with its own formulas, since a sign that points the wrong way gives energy instead of
//     storing or removing it;
// and then compares h with the method's critical step on the scene (stability.hpp). It blames h
// only when every law held and h is beyond that step.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"

#include <limits>
#include <string>

namespace springlab {

/// What the diagnosis found broken, the first of these in this order.
enum class BrokenLaw {
  none,          ///< nothing: the run was not replayed (too large) or stayed within every law
  start_forces,  ///< the forces at the start state are not finite numbers
  momentum,      ///< Σ m_i v_i changed although nothing outside the springs acts (2.4)
  gravity,       ///< Σ m_i v_i changed by other than t·Σ m_i·g under gravity alone (5.2)
  symmetry,      ///< a mirror-symmetric start lost its symmetry (2.1), (2.2)
  energy,        ///< springs or dampers gave energy: a force points the wrong way (1.1), (1.2)
  step_size,     ///< every law held and h is beyond the method's critical step
  step_function  ///< every law held and h is within the critical step: the step itself
};

/// The diagnosis of a divergence: which law broke, when, by how much, where to look, in words.
/// Whether the code under test's forces, measured about the scene at rest, are those of (1.1) and
/// (1.2) there (so the formula's step limit is the run's): not checked for the kit's own model or a
/// scene beyond the exact budget; not measured when the code threw or gave no finite value; grow:
/// they differ, and make some motion grow in exact time (no step is stable or to blame).
enum class ForcesAtRest { not_checked, as_formulas, differ, grow, not_measured };

struct Diagnosis {
  BrokenLaw law = BrokenLaw::none;
  double time = std::numeric_limits<double>::quiet_NaN();  ///< s, when the law first broke
  /// How much: kg·m/s (momentum, gravity), m (symmetry), the wrong force's share
  /// as a factor (energy: -1 for a flipped sign), h / h_c (step_size).
  double amount = 0.0;
  std::string equation;   ///< the handout's equation to check, e.g. "(2.4)"; empty if none
  std::string words;      ///< plain sentences for the student
  double step = 0.0;      ///< h, s
  CriticalStep critical;  ///< h_c of the run's method on this scene (not_computed if unknown),
                          ///< of the forces that ran (see forces_at_rest)
  ForcesAtRest forces_at_rest = ForcesAtRest::not_checked;
  CriticalStep formula_critical;  ///< h_c of (1.1) and (1.2)'s forces, when those differ
  double own_growth_rate = 0.0;   ///< 1/s: the largest Re λ of the measured model, when it grows
  double growth = std::numeric_limits<double>::quiet_NaN();  ///< per step at h, if computed
  double replayed = 0.0;                                     ///< s of the run the replay watched
  bool replayed_all = false;
};

/// The replay's budget: scenes beyond it are diagnosed by the step limit alone, and say so.
struct DiagnosisBudget {
  int particles = 100000;       ///< larger scenes keep no start state and are not replayed
  double particle_steps = 3e7;  ///< the replay stops after this many particles × steps
  int exact_particles = exact_particles_max;  ///< eigen-solves (exact h_c) up to this size
};

/// The critical step of the scene's integrator (parameters.integrator), linearised about the
/// grid at rest (as `springlab-run --stability` does) when the scene is a rows×cols grid, else
/// about its particles' positions: exact up to budget.exact_particles particles (as
/// stability_report decides), else its estimates from the bounds, and for explicit-euler c/ω²
/// (equation (1.6)) of the fastest mode, found by power iteration. `growth` receives the growth
/// factor per step at the scene's h when exact and h is beyond h_c.
CriticalStep scene_critical_step(const Scene& scene, const DiagnosisBudget& budget = {},
                                 double* growth = nullptr);

/// The kit's reference implementation, which the diagnosis runs on the same scene at the same h
/// before it blames the code under test or h (programs that hold it register it:
/// common/impl/registry.cpp; a grader's test program holds no reference of its task, and does
/// not). Null: none.
void set_diagnosis_reference(const Implementation* reference);
/// The one set_diagnosis_reference registered (null: none).
const Implementation* registered_diagnosis_reference();

/// Replays `steps` steps of h from `start` (the scene as it was at time `start_time`, its
/// parameters saying h and the integrator) with impl, watching the laws above, and diagnoses.
/// Calls impl exactly as the run did (the same inputs in the same order), nothing else of it.
Diagnosis diagnose_divergence(const Scene& start, const Implementation& impl, double start_time,
                              long steps, const DiagnosisBudget& budget = {});

}  // namespace springlab
