// The speed–accuracy study (issue 5): every method on the lab's scenes, against an exact or a
// checked reference solution, measured in error, energy error, force evaluations and wall time.
// Written for students to read as a worked example of how methods are compared fairly: the same
// force code, the same output times, the same error measure for every method.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/scene.hpp"
#include "springlab/types.hpp"

#include <cmath>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace springlab::tradeoff {

/// What a study runs; --quick shrinks every part of it.
struct StudyOptions {
  bool quick = false;
  /// --impl student: the student's explicit Euler (task 1) and Verlet (task 4) beside the kit's
  /// methods, in about a minute (student_options in main.cpp).
  bool student = false;
  /// The comparisons of XPBD with small steps (xpbd_study.cpp): the full study only.
  bool xpbd = false;
  int repeats = 3;         ///< wall time is the minimum over this many runs
  double duration = 5.12;  ///< s, 512 lab steps: a whole number of every step in the sweep
  double sample = 0.04;    ///< s, the output times errors are measured at (a multiple of h ≤ it)
  /// Steps h = h_lab·2^k from k_min to k_max.
  int k_min = -6, k_max = 5;
  int k_min_fabric = -6;  ///< the fabric's smallest k: its runs at tiny steps cost the most
  std::vector<double> tolerances{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  std::vector<std::string> scenes{"two-masses", "grid", "fabric"};
};

/// The reference motion at the output times t_j = j·sample (state and total energy).
struct Trajectory {
  std::vector<double> time;       ///< s
  std::vector<Vectors> position;  ///< m
  std::vector<double> energy;     ///< J, kinetic + spring + gravity (zero at the start positions)
};

/// A scene of the study and how its error is measured.
struct Scenario {
  std::string name;            ///< "two-masses", "grid", "fabric"
  std::string title;           ///< for figures and the page
  SceneParameters params;      ///< the lab's scene, step and integrator set per run
  Trajectory reference;        ///< exact (two masses) or computed (reference.cpp)
  std::string reference_note;  ///< how the reference was made and how accurate it is, for the page
  double reference_error = 0.0;  ///< its estimated largest position error, m
  double energy_scale = 0.0;     ///< J: the largest |E_ref(t)|, what energy errors are divided by
};

Scenario make_scenario(const std::string& name, const StudyOptions& options);

/// One run of one method at one step (or tolerance) on one scene.
struct Run {
  std::string scene, method;
  double h = 0.0;          ///< s; for dopri5 the mean step taken
  double tolerance = 0.0;  ///< dopri5's abs = rel tolerance, 0 for fixed steps
  bool stable = true;
  std::string unstable_why;   ///< empty when stable
  double max_error = 0.0;     ///< m, the largest position error over the output times
  double end_error = 0.0;     ///< m, at the last output time
  double energy_error = 0.0;  ///< the largest |E - E_ref| / energy_scale over the output times
  long evaluations = 0;       ///< force evaluations a(r, v)
  long steps = 0;
  double wall = 0.0;           ///< s, minimum over the repeats
  std::vector<double> energy;  ///< J at the output times (kept for the lab step only)
};

/// The kit's integrators (integrator_names()), then Odeint's fixed-step RK4 and adaptive
/// Dormand–Prince.
std::vector<std::string> kit_methods();

/// The student's methods are named "yours:explicit-euler" and "yours:verlet": the integrator
/// after the colon, run on student_implementation(1) or (4) (the student's task with the
/// reference for the others).
inline const std::string yours = "yours:";
bool is_students(const std::string& method);
/// The integrator a method runs: "verlet" for "yours:verlet".
std::string integrator_of(const std::string& method);
/// As the page shows it: "verlet (yours)".
std::string shown(const std::string& method);

/// The fixed-step methods a study runs: the kit's, then the student's when options.student.
std::vector<std::string> study_methods(const StudyOptions& options);
inline const std::string odeint_rk4 = "odeint-rk4";
inline const std::string odeint_dopri5 = "odeint-dopri5";

/// Reports what is running, how far along the study is and the time left, on stderr.
class Progress {
 public:
  explicit Progress(double total_work) : total_(total_work) {}
  void begin(const std::string& what);
  void done(double work);

 private:
  double total_, done_ = 0.0;
  double start_ = -1.0, last_print_ = -10.0;
  std::string what_;
};

/// Estimated work of a run (force evaluations × particles), for the progress's time estimate.
double run_work(const Scenario& s, const std::string& method, double h, double duration);

/// Runs one method at step h (or tolerance `tolerance` for dopri5) `repeats` times.
Run run_method(const Scenario& s, const std::string& method, double h, double tolerance,
               const StudyOptions& options);

/// The smallest k of the steps h_lab·2^k run on scene s.
int k_min(const Scenario& s, const StudyOptions& options);

/// Every run of the study on one scene: each method over the steps, dopri5 over the tolerances.
std::vector<Run> run_scene(const Scenario& s, const StudyOptions& options, Progress& progress);

/// The critical step of a method on a scene: from theory (stability.hpp) and by bisection.
struct StepLimit {
  std::string scene, method;
  double theory = 0.0;      ///< s
  std::string source;       ///< how theory got it (exact formula, bisection, estimate)
  std::string about;        ///< the state theory linearises about ("at rest", …)
  double measured = 0.0;    ///< s, 0 when not measured
  double half_width = 0.0;  ///< s, of the bracket measured is the middle of (0: a bisection's end)
  std::string how;          ///< how it was measured
};

std::vector<StepLimit> critical_steps(const Scenario& s, const StudyOptions& options,
                                      Progress& progress);
double critical_work(const Scenario& s, const StudyOptions& options);

/// A least-squares slope of log(error) against log(h).
struct Order {
  std::string scene, method;
  int theory = 0;
  double measured = 0.0;            ///< NaN when too few points lie in the asymptotic range
  double h_from = 0.0, h_to = 0.0;  ///< s, the fitted range
  int points = 0;
  bool outside_range = false;  ///< fitted over the smallest steps, their errors out of the range
};

std::vector<Order> measured_orders(const Scenario& s, const std::vector<Run>& runs,
                                   const StudyOptions& options);
int theoretical_order(const std::string& method);

/// The cheapest stable run reaching error ≤ level, by wall time or by force evaluations.
const Run* cheapest(const std::vector<Run>& runs, const std::string& scene, double level,
                    bool by_evaluations);

/// Force evaluations per step a method may use (integrator.hpp), on scene s at step h.
double evaluation_budget(const Scenario& s, const std::string& method, double h);

/// Wall time of one force evaluation on the scene, s (minimum over a few batches).
double evaluation_time(const Scenario& s);

/// The linear-solve work of `steps` steps of an implicit method on a scene, counted through
/// Integrator::solver_work (never timed, so a busy machine cannot change it), beside what
/// conjugate-gradient theory allows a step.
struct SolverCount {
  long steps = 0;
  long most_products = 0;      ///< the largest number of products A x in one step
  double mean_products = 0;    ///< per step
  long factorisations = 0;     ///< LDLᵀ fallbacks in all
  long products_allowed = 0;   ///< cg_product_bound for the scene at its step
  double condition_bound = 0;  ///< the bound on the preconditioned matrix's condition number
};

SolverCount count_solver_work(const Scenario& s, const std::string& method, long steps);

/// Products a conjugate-gradient solve of implicit Euler's A = M + hC + h²K needs at most on the
/// scene: with κ bounding the Jacobi-preconditioned A's condition number, the error falls by
/// ρ = (√κ − 1)/(√κ + 1) an iteration in A's norm, and the residual by at least ρ^k / (2√κ) after
/// k, so k = ln(2√κ/tol)/ln(1/ρ) iterations reach the tolerance, plus the first residual's product.
/// κ from the springs: hC + h²K ≼ Σ_s (h b + h² k)(e_p − e_q)(e_p − e_q)ᵀ ⊗ I (every spring block
/// has eigenvalues in [0, h b + h² k] once compressed springs are clamped), so A's eigenvalues lie
/// in [m_min, m_max + 2 max_i Σ_{s ∋ i}(h b_s + h² k_s)], and so do its diagonal's entries.
long cg_product_bound(const Scene& scene, double h, double tolerance, double* condition = nullptr);

/// One run of the XPBD comparisons (xpbd_study.cpp), observed every frame.
struct XpbdRun {
  std::string label;  ///< "xpbd 8×1", "implicit-euler h = 0.02"
  bool stable = true;
  std::string why;             ///< when it diverged
  double error = 0.0;          ///< m, the largest distance to the reference (when there is one)
  double strain = 0.0;         ///< the largest (L − ℓ0)/ℓ0 over the springs and the run
  double frame_seconds = 0.0;  ///< wall time of a frame, s (the run's own, measuring included)
  long projections = 0;        ///< XPBD's constraint projections in all
  long evaluations = 0;        ///< a(r, v) calls in all
  std::vector<double> time;    ///< s, every frame
  std::vector<double> energy;  ///< (E − floor)/(E_0 − floor) at those times
};

struct XpbdPair {
  bool stiff = false;  ///< the fabric with k × stiff_factor
  int n = 1;
  XpbdRun substeps;    ///< n substeps × 1 iteration
  XpbdRun iterations;  ///< 1 substep × n iterations
};

struct XpbdStiffness {
  double factor = 1.0;        ///< k × this for every family
  std::vector<XpbdRun> runs;  ///< each method at the frame budget
};

/// The three comparisons of XPBD with small steps (Macklin et al. 2019) on the kit's fabric.
struct XpbdStudy {
  double frame = 0.0, duration = 0.0;  ///< s
  double stiff_factor = 0.0;
  double lab_reference_error = 0.0, stiff_reference_error = 0.0;    ///< m
  double lab_reference_strain = 0.0, stiff_reference_strain = 0.0;  ///< largest (L − ℓ0)/ℓ0
  std::vector<XpbdPair> pairs;                                      ///< claim 1
  double budget_seconds = 0.0;           ///< implicit Euler's wall time a frame
  double evaluation_seconds = 0.0;       ///< one force evaluation's, for scale
  int budget_substeps = 1;               ///< XPBD substeps (1 iteration) within the budget
  int budget_symplectic_steps = 1;       ///< symplectic Euler steps within it
  double equilibrium_energy = 0.0;       ///< J, the hanging equilibrium's
  std::vector<XpbdRun> energy;           ///< claim 2: the reference (rk4), then the methods
  std::vector<XpbdStiffness> stiffness;  ///< claim 3
};

/// Runs the comparisons on the study's fabric scenario (its reference included).
XpbdStudy xpbd_study(const Scenario& fabric, const StudyOptions& options, Progress& progress);
void write_xpbd_section(std::ostream& out, const XpbdStudy& x, const std::string& figures,
                        const std::string& machine);
/// gnuplot commands drawing its two figures into `figures` (data files written into `dir`).
std::string write_xpbd_figures(const XpbdStudy& x, const std::string& dir,
                               const std::string& figures);

/// Where the fabric hangs (critical.cpp): the scene at rest there, and how well it balances.
struct Equilibrium {
  Scene scene;
  double residual = 0.0;  ///< m/s², the largest acceleration left
  int newton_steps = 0;
};
Equilibrium hanging_equilibrium(const SceneParameters& params);

/// Task 4's damped scene (common/scenes/task4-damped.toml): the lab's Verlet, textbook Verlet
/// and, with --impl student, the student's, at the scene's step for its duration.
struct DampedRun {
  std::string method;  ///< "verlet", "textbook-verlet", "yours:verlet"
  bool stable = true;
  std::string why;  ///< how it ended when not stable
  double evaluations_a_step = 0.0;
  std::vector<double> time;    ///< s
  std::vector<double> energy;  ///< J, total, every step while finite
};

struct DampedScene {
  double h = 0.0;                ///< the scene's step, s
  double textbook_limit = 0.0;   ///< s: symplectic Euler's exact limit, textbook Verlet's too
  double verlet_limit = 0.0;     ///< s: 2/ω_max
  double iteration_limit = 0.0;  ///< s: where task 4's iteration stops settling in time
  double omega_max = 0.0;        ///< rad/s
  double zeta = 0.0;             ///< the damping ratio of the mode at ω_max, φᵀCφ/(2ω)
  std::vector<DampedRun> runs;
};

DampedScene damped_scene(const StudyOptions& options);
void write_damped_section(std::ostream& out, const DampedScene& d, const std::string& figures);
std::string write_damped_figure(const DampedScene& d, const std::string& dir,
                                const std::string& figures);

struct Results {
  StudyOptions options;
  std::vector<Scenario> scenarios;
  std::vector<Run> runs;
  std::vector<StepLimit> critical;
  std::vector<Order> orders;
  std::vector<double> evaluation_seconds;      ///< per scenario
  double implicit_fabric_cost = std::nan("");  ///< step_cost of implicit-euler on the fabric
  SolverCount implicit_fabric_solves;          ///< its counted solver work at the lab step
  double total_seconds = 0.0;
  std::optional<XpbdStudy> xpbd;  ///< the full study only
  DampedScene damped;
  std::string machine;  ///< the processor, cores and load it ran with
};

/// What one step of a run cost, in units of one force evaluation's time on its scene: the wall
/// time a step over evaluation_time. Counts the integrator's own work (an implicit solve) too.
double cost_in_evaluations(const Results& r, const Run& run);

/// An implicit step at the lab's values may cost at most this many force evaluations (issue 5).
/// Reported from timings on the page; the --quick check counts products instead (SolverCount).
inline constexpr double implicit_step_budget = 20.0;

/// What a step of `method` costs on scene s at its lab step, in force evaluations' time: the
/// median over 7 rounds of a batch of steps timed against as many evaluations right after.
double step_cost(const Scenario& s, const std::string& method);

/// The --quick checks; each failure as one line (expected, measured, what it means).
std::vector<std::string> check(const Results& r);

/// Where the student's explicit Euler and Verlet differ from theory or from the kit's same
/// method (order, critical step, error, the damped scene), one line each, in the tests' words.
std::vector<std::string> student_findings(const Results& r);

void write_csv(const Results& r, const std::string& dir);
/// gnuplot data and scripts in `dir`, figures (SVG) into `figures`; false when gnuplot failed.
bool write_figures(const Results& r, const std::string& dir, const std::string& figures);
void write_page(const Results& r, const std::string& page, const std::string& figures,
                const std::string& out_dir);

/// "1.2e-05", "0.01", "3.4 ms": short numbers for tables and messages.
std::string number(double x, int digits = 3);
std::string seconds(double s);

}  // namespace springlab::tradeoff
