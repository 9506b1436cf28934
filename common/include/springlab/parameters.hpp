// Every value a scene is made from, in one struct with SI units and the lab's values as defaults,
// and the one table (for_each_field) that names each field for --set, scene files, validation
// and, later, the viewer's sliders.
#pragma once

#include "springlab/types.hpp"

#include <limits>
#include <numbers>
#include <string>
#include <string_view>

namespace springlab {

/// The values shared by every spring of one family (handout equation (3.2)).
struct SpringFamilyParameters {
  bool enabled = true;       ///< whether the scene has springs of this family at all
  double k = 20.0;           ///< stiffness, N/m
  double b = 0.1;            ///< damping coefficient of each spring's damper, N·s/m
  double rest_length = 1.0;  ///< ℓ0, m
};

/// Gravity, equation (5.2): F_i += m_i g on every particle (a pinned one is then held by (5.5)).
struct GravityParameters {
  bool enabled = false;           ///< whether the scene has gravity at all
  Vec2 acceleration{0.0, -9.81};  ///< g, m/s² (y points up)
};

/// Wind, equation (5.3): a drag F_i = c (w(t, r_i) - v_i) towards the wind's velocity w, whose
/// gusts (wind.hpp) vary smoothly in time and along the wind, the same for the same seed.
struct WindParameters {
  bool enabled = false;      ///< whether the scene has wind at all
  Vec2 direction{1.0, 0.0};  ///< where it blows to (any length; only the direction counts)
  double speed = 8.0;        ///< mean wind speed |w|, m/s
  double drag = 0.1;         ///< c, drag of one particle, N·s/m
  double gustiness = 0.5;    ///< gusts change the speed by up to this fraction of it
  double gust_period = 3.0;  ///< typical time between gusts, s
  int seed = 1;              ///< the gusts' pattern: the same seed, the same wind
};

/// XPBD (integrator "xpbd", handout/integrators.md): each step h is split into `substeps`
/// substeps of h/substeps, and in each the springs' distance constraints are projected
/// `iterations` times (Gauss–Seidel passes over the springs). Its cost a step is
/// substeps × iterations passes over the springs.
struct XpbdParameters {
  int substeps = 10;   ///< substeps a step (each h/substeps long), a count
  int iterations = 1;  ///< Gauss–Seidel passes over the constraints in each substep, a count
};

/// One scene: a rows×cols grid of equal masses, its springs and forces, its start and how to step
/// it. The defaults are the lab's values (lecture appendix) on the task 1 scene.
/// Particle sets (pinned, displaced, pushed) are written as text: "none", "all", "top-row",
/// "bottom-row", "left-column", "right-column", "top-corners", "corners", or indices and ranges
/// such as "0,4,8" or "0-9" (selection.hpp).
struct SceneParameters {
  std::string name = "custom";  ///< shown by the runner and the viewer
  int task = 0;                 ///< the lab task the scene belongs to (1–5), 0 for none
  int rows = 1;                 ///< grid rows (particles per column)
  int cols = 2;                 ///< grid columns (particles per row)
  double spacing = 1.0;         ///< distance between grid neighbours at the start, m
  double mass = 0.2;            ///< mass of every particle, kg
  SpringFamilyParameters structural{true, 20.0, 0.1, 1.0};              ///< task 2
  SpringFamilyParameters shear{false, 7.0, 0.05, std::numbers::sqrt2};  ///< task 3
  SpringFamilyParameters bend{false, 10.0, 0.05, 2.0};                  ///< task 5
  GravityParameters gravity;                                            ///< task 5
  WindParameters wind;                                                  ///< task 5
  std::string pinned = "none";                ///< particles that never move (task 5)
  std::string displaced = "1";                ///< particles moved from their grid position at t = 0
  Vec2 displacement{0.2, 0.0};                ///< how far each of them is moved, m
  std::string pushed = "none";                ///< particles the applied force acts on (task 5)
  Vec2 push{0.0, 0.0};                        ///< the applied force on each pushed particle, N
  double push_duration = 0.0;                 ///< the push acts while t < push_duration, s
  double step = 0.01;                         ///< h, the fixed time step, s
  double duration = 10.0;                     ///< simulated time of a run, s
  std::string integrator = "explicit-euler";  ///< an integrator name (see integrator.hpp)
  XpbdParameters xpbd;                        ///< substeps and iterations of "xpbd"
};

/// The allowed values of a numeric field: min ≤ value ≤ max, with strict ends where *_open.
struct Range {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
  bool max_open = false;
  bool integer = false;

  bool contains(double value) const;  ///< false for NaN and infinities
  /// As text, e.g. "1e-06 <= mass <= 1e+09 kg".
  std::string describe(std::string_view key, std::string_view unit) const;
};

/// How for_each_field describes a field to its visitor.
struct FieldInfo {
  std::string_view key;      ///< as written after --set and in scene files, e.g. "structural.k"
  std::string_view unit;     ///< SI unit, empty for counts, switches and names
  std::string_view meaning;  ///< one line for help texts
  Range range;               ///< allowed values of a numeric field
};

inline constexpr int max_grid_side = 100000;         ///< particles along one side of a grid
inline constexpr double max_steps = 1e10;            ///< steps in one run (duration / step)
inline constexpr std::size_t max_text_bytes = 4096;  ///< of a text field (name, pinned, …)

/// Calls visit(info, value) for every field of p, where value is an int&, double&, bool& or
/// std::string& (const when p is const). The one list of every scene parameter.
template <class Params, class Visitor>
void for_each_field(Params& p, Visitor&& visit) {
  constexpr double big = 1e9;
  // Masses and lengths from a micrometre and a microgram up: below that, k/m and forces over
  // lengths leave the range of doubles (a subnormal mass passed a check of "> 0" and made
  // every frequency infinite).
  const Range positive{1e-6, big};
  const Range non_negative{0.0, big};
  const Range any_length{-1e6, 1e6};
  const Range side{1, max_grid_side, false, false, true};
  visit(FieldInfo{"name", "", "the scene's name", {}}, p.name);
  visit(FieldInfo{"task", "", "the lab task it belongs to, 0 for none", {0, 5, false, false, true}},
        p.task);
  visit(FieldInfo{"rows", "", "grid rows", side}, p.rows);
  visit(FieldInfo{"cols", "", "grid columns", side}, p.cols);
  visit(FieldInfo{"spacing", "m", "distance between grid neighbours at the start", positive},
        p.spacing);
  visit(FieldInfo{"mass", "kg", "mass of every particle", positive}, p.mass);
  visit(FieldInfo{"structural.enabled", "", "structural springs on or off", {}},
        p.structural.enabled);
  visit(FieldInfo{"structural.k", "N/m", "structural stiffness", non_negative}, p.structural.k);
  visit(FieldInfo{"structural.b", "N*s/m", "structural damping", non_negative}, p.structural.b);
  visit(FieldInfo{"structural.rest_length", "m", "structural rest length", positive},
        p.structural.rest_length);
  visit(FieldInfo{"shear.enabled", "", "shear springs on or off", {}}, p.shear.enabled);
  visit(FieldInfo{"shear.k", "N/m", "shear stiffness", non_negative}, p.shear.k);
  visit(FieldInfo{"shear.b", "N*s/m", "shear damping", non_negative}, p.shear.b);
  visit(FieldInfo{"shear.rest_length", "m", "shear rest length", positive}, p.shear.rest_length);
  visit(FieldInfo{"bend.enabled", "", "bend springs on or off", {}}, p.bend.enabled);
  visit(FieldInfo{"bend.k", "N/m", "bend stiffness", non_negative}, p.bend.k);
  visit(FieldInfo{"bend.b", "N*s/m", "bend damping", non_negative}, p.bend.b);
  visit(FieldInfo{"bend.rest_length", "m", "bend rest length", positive}, p.bend.rest_length);
  const Range any_acceleration{-1e4, 1e4};
  visit(FieldInfo{"gravity.enabled", "", "gravity on or off", {}}, p.gravity.enabled);
  visit(FieldInfo{"gravity.x", "m/s^2", "gravity along x", any_acceleration},
        p.gravity.acceleration.x());
  visit(FieldInfo{"gravity.y", "m/s^2", "gravity along y (y points up)", any_acceleration},
        p.gravity.acceleration.y());
  visit(FieldInfo{"wind.enabled", "", "wind on or off", {}}, p.wind.enabled);
  visit(FieldInfo{"wind.direction.x", "", "where the wind blows to, x", {-1.0, 1.0}},
        p.wind.direction.x());
  visit(FieldInfo{"wind.direction.y", "", "where the wind blows to, y", {-1.0, 1.0}},
        p.wind.direction.y());
  visit(FieldInfo{"wind.speed", "m/s", "mean wind speed", {0.0, 1e3}}, p.wind.speed);
  visit(FieldInfo{"wind.drag", "N*s/m", "drag of one particle", {0.0, 1e3}}, p.wind.drag);
  visit(FieldInfo{"wind.gustiness", "", "gusts change the speed by this fraction", {0.0, 1.0}},
        p.wind.gustiness);
  visit(FieldInfo{"wind.gust_period", "s", "typical time between gusts", {1e-3, 1e6}},
        p.wind.gust_period);
  visit(FieldInfo{"wind.seed", "", "the gusts' pattern", {0, 1e9, false, false, true}},
        p.wind.seed);
  visit(FieldInfo{"pinned", "", "particles that never move (e.g. top-row, 0,19)", {}}, p.pinned);
  visit(FieldInfo{"displaced", "", "particles moved at the start (e.g. 8, top-row)", {}},
        p.displaced);
  visit(FieldInfo{"displacement.x", "m", "their displacement along x", any_length},
        p.displacement.x());
  visit(FieldInfo{"displacement.y", "m", "their displacement along y", any_length},
        p.displacement.y());
  visit(FieldInfo{"pushed", "", "particles the applied force acts on", {}}, p.pushed);
  visit(FieldInfo{"push.x", "N", "applied force on each, along x", {-1e6, 1e6}}, p.push.x());
  visit(FieldInfo{"push.y", "N", "applied force on each, along y", {-1e6, 1e6}}, p.push.y());
  visit(FieldInfo{"push_duration", "s", "the push acts while t < this", {0.0, 1e7}},
        p.push_duration);
  visit(FieldInfo{"step", "s", "h, the fixed time step", {0.0, 10.0, true}}, p.step);
  visit(FieldInfo{"duration", "s", "simulated time of a run", {0.0, 1e7}}, p.duration);
  visit(FieldInfo{"integrator", "", "the integrator's name", {}}, p.integrator);
  visit(FieldInfo{"xpbd.substeps", "", "xpbd: substeps a step", {1, 1e4, false, false, true}},
        p.xpbd.substeps);
  visit(
      FieldInfo{
          "xpbd.iterations", "", "xpbd: constraint passes a substep", {1, 1e4, false, false, true}},
      p.xpbd.iterations);
}

/// Checks every field against its range and the fields against each other (rows·cols ≥ 2, the
/// grid fits in memory, the particle sets name existing particles, the wind has a direction,
/// duration/step ≤ max_steps, the integrator is known). Throws
/// InvalidParameter naming the field, the value and the allowed range.
void validate(const SceneParameters& p);

/// validate() without the memory guard, for the parameters of a scene already built: its
/// memory is taken, and counting it again as still needed refused runs that fit.
void validate_built(const SceneParameters& p);

/// Sets the field `key` from text, as `--set key=value` does: "40", "true", "verlet". Throws
/// InvalidParameter for an unknown key (suggesting the nearest one), text that is not a value of
/// the field's type, or a value out of range.
void set_parameter(SceneParameters& p, std::string_view key, std::string_view value);

/// set_parameter whose messages show the value as `written` (a scene file's own text, e.g.
/// 0.20000000000000001 or "3" with its quotes) rather than as `value`.
void set_parameter(SceneParameters& p, std::string_view key, std::string_view value,
                   std::string_view written);

/// set_parameter with a number, passed on exactly (as the front ends' --dt and --duration do).
void set_number(SceneParameters& p, std::string_view key, double value);

/// "KEY=VALUE", as the front ends' --set takes it: set_parameter(p, KEY, VALUE). Throws
/// InvalidParameter naming --set for text without '='.
void set_assignment(SceneParameters& p, std::string_view assignment);

/// The known field name nearest to `key` (edit distance), for "did you mean" hints; empty when
/// none is close (more than a third of the key's letters would change).
std::string nearest_key(std::string_view key);

/// Whether `name` is a table of parameters: "shear", "wind", "wind.direction".
bool is_parameter_table(std::string_view name);

/// What to say of an unknown key: the close key meant, else the keys of its table, else the
/// parameters there are.
std::string unknown_key(std::string_view key);

}  // namespace springlab
