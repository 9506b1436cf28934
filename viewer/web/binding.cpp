// The page's binding (viewer/web/README.md): JavaScript drives the desktop viewer's Session
// (viewer/gui/session.hpp), which runs the kit's core and task code with no graphics, through
// embind. Nothing here computes physics: it hands the page the state to draw, passes the user's
// edits to the Session, and turns the kit's errors into their own words.
#include "gui/session.hpp"

#include "springlab/comparison.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/parameters.hpp"
#include "springlab/scene.hpp"
#include "springlab/simulation.hpp"

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

namespace springlab::web {
namespace {

using emscripten::val;

// Scene files the user opens are written here and loaded by their bare name, so that the kit's
// messages name the file as the user knows it ("bad.toml, line 3: ...").
constexpr const char* uploads = "/uploads";

val text_list(const std::vector<std::string>& items) {
  val out = val::array();
  for (const std::string& item : items)
    out.call<void>("push", item);
  return out;
}

// A JavaScript copy of n values: the page keeps it past the next step (which may move memory).
template <class T>
val typed_copy(const char* type, const T* data, std::size_t n) {
  return val::global(type).new_(emscripten::typed_memory_view(n, data));
}

val vectors(const Vectors& v) {  // x0, y0, x1, y1, ... (Eigen's columns, in order)
  return typed_copy("Float64Array", v.data(), std::size_t(v.size()));
}

template <class T>
const char* type_name() {
  if constexpr (std::is_same_v<T, bool>) return "bool";
  if constexpr (std::is_same_v<T, int>) return "int";
  if constexpr (std::is_same_v<T, double>) return "real";
  return "text";
}

const char* kind_name(view::Problem::Kind kind) {
  switch (kind) {
    case view::Problem::Kind::none:
      return "none";
    case view::Problem::Kind::diverged:
      return "diverged";
    case view::Problem::Kind::not_implemented:
      return "not-implemented";
    case view::Problem::Kind::invalid:
      return "invalid";
    case view::Problem::Kind::failed:
      break;
  }
  return "failed";
}

// The last path component of what the browser calls the file; "scene.toml" for none.
std::string bare_name(const std::string& name) {
  std::string bare = std::filesystem::path(name).filename().string();
  return bare.empty() || bare == "." || bare == ".." ? "scene.toml" : bare;
}

}  // namespace

/// One Session as the page sees it. Every method that takes the user's text returns the kit's
/// message when it refuses it ("" when it took it); the simulation's own problems (divergence,
/// a task not written, a scene that cannot be loaded) are in problem().
class Lab {
 public:
  explicit Lab(const std::string& scene) : session_(scene) {}

  void load(const std::string& scene) { session_.load(scene); }

  /// A scene file's text, as opened in the browser: written to the page's file system under its
  /// bare name and loaded as `springlab-run --scene NAME` would load it.
  void load_text(const std::string& name, const std::string& text) {
    std::filesystem::create_directories(uploads);
    const std::string bare = bare_name(name);
    std::ofstream(std::string(uploads) + "/" + bare, std::ios::binary) << text;
    std::filesystem::current_path(uploads);
    session_.load(bare);
  }

  std::string source() const { return session_.source(); }

  /// Every scene parameter: key, unit, meaning, type, its value now and as loaded, its range.
  val fields() const {
    std::vector<val> loaded;
    for_each_field(session_.loaded_parameters(),
                   [&](const FieldInfo&, const auto& value) { loaded.push_back(val(value)); });
    val out = val::array();
    std::size_t index = 0;
    for_each_field(session_.parameters(), [&](const FieldInfo& info, const auto& value) {
      using T = std::decay_t<decltype(value)>;
      val field = val::object();
      field.set("key", std::string(info.key));
      field.set("unit", std::string(info.unit));
      field.set("meaning", std::string(info.meaning));
      field.set("type", std::string(type_name<T>()));
      field.set("value", val(value));
      field.set("loaded", loaded[index++]);
      if constexpr (!std::is_same_v<T, std::string> && !std::is_same_v<T, bool>) {
        field.set("min", info.range.min);
        field.set("max", info.range.max);
        field.set("minOpen", info.range.min_open);
        field.set("maxOpen", info.range.max_open);
        field.set("allowed", info.range.describe(info.key, info.unit));
      }
      out.call<void>("push", field);
    });
    return out;
  }

  /// Sets a parameter from text, as `--set KEY=VALUE` does, and applies it mid-motion: "" when
  /// taken, else the kit's message (the field, the value and what is allowed) and nothing changes.
  std::string set(const std::string& key, const std::string& text) {
    SceneParameters changed = session_.parameters();
    try {
      set_parameter(changed, key, text);
    } catch (const InvalidParameter& error) {
      return error.what();
    }
    session_.parameters() = changed;
    session_.apply();
    return "";
  }

  void reset() { session_.reset(); }
  bool running() const { return session_.running(); }
  void set_running(bool running) { session_.set_running(running); }
  /// Advances a frame that lasted `seconds` of wall time by the viewer's pacing (whole steps h
  /// at the real-time factor, the fraction carried over), at most `most` steps (the rest are
  /// dropped: a slow scene runs slower than real time rather than at a few frames a second);
  /// returns the steps taken.
  double frame(double seconds, double most) {
    const long steps = session_.steps_due(seconds, long(std::max(most, 1.0)));
    session_.advance(steps);
    return double(steps);
  }
  double dropped_steps() const { return double(session_.dropped_steps()); }
  void single_step() { session_.single_step(); }
  /// `steps` steps h now, paused or not (the tests' way to a given step count).
  void advance(double steps) {
    if (session_.problem().kind == view::Problem::Kind::none) session_.advance(long(steps));
  }
  void set_real_time_factor(double factor) { session_.pacing().real_time_factor = factor; }

  val state() const {
    val out = val::object();
    const Simulation* sim = session_.primary();
    out.set("time", session_.time());
    out.set("steps", sim ? double(sim->steps_taken()) : 0.0);
    out.set("particles", sim ? sim->particles().size() : 0);
    out.set("springs", sim ? double(sim->scene().springs.size()) : 0.0);
    out.set("rows", session_.parameters().rows);
    out.set("cols", session_.parameters().cols);
    out.set("builds", session_.builds());
    out.set("freshStarts", session_.fresh_starts());
    out.set("running", session_.running());
    out.set("grabbed", session_.grabbed());
    out.set("task", session_.task());
    out.set("name", session_.parameters().name);
    out.set("integrator", session_.parameters().integrator);
    out.set("step", session_.parameters().step);
    out.set("fastForces", sim && sim->fast_forces());
    if (sim) {
      const Diagnostics d = sim->diagnostics();
      out.set("kinetic", d.kinetic);
      out.set("potential", d.all_potential());
      out.set("total", d.total());
      out.set("momentumX", d.momentum.x());
      out.set("momentumY", d.momentum.y());
    }
    return out;
  }

  /// Positions (x0, y0, x1, y1, ... in m) of the chosen code's run, or of the reference's
  /// beside it (`reference`); null when there is none.
  val positions(bool reference) const {
    const Simulation* sim = reference ? session_.reference() : session_.primary();
    return sim ? vectors(sim->particles().position) : val::null();
  }
  val velocities(bool reference) const {
    const Simulation* sim = reference ? session_.reference() : session_.primary();
    return sim ? vectors(sim->particles().velocity) : val::null();
  }
  val pinned() const {
    const Simulation* sim = session_.primary();
    if (!sim) return val::null();
    std::vector<unsigned char> flags;
    for (int i = 0; i < sim->particles().size(); ++i)
      flags.push_back(session_.pinned(i) ? 1 : 0);
    return typed_copy("Uint8Array", flags.data(), flags.size());
  }

  /// The springs: `ends` (p0, q0, p1, q1, ...), `rest` (ℓ0, m) and `family` (0 structural,
  /// 1 shear, 2 bend); null without a simulation.
  val springs() const {
    const Simulation* sim = session_.primary();
    if (!sim) return val::null();
    const std::vector<Spring>& springs = sim->scene().springs;
    std::vector<int> ends;
    std::vector<double> rest;
    std::vector<unsigned char> family;
    for (const Spring& s : springs) {
      ends.push_back(s.p);
      ends.push_back(s.q);
      rest.push_back(s.rest_length);
      family.push_back(static_cast<unsigned char>(s.family));
    }
    val out = val::object();
    out.set("ends", typed_copy("Int32Array", ends.data(), ends.size()));
    out.set("rest", typed_copy("Float64Array", rest.data(), rest.size()));
    out.set("family", typed_copy("Uint8Array", family.data(), family.size()));
    return out;
  }

  /// The plots' samples (one a frame, the last 10 s): time, kinetic, potential, total,
  /// momentumX, momentumY.
  val history() const {
    const view::History& h = session_.history();
    val out = val::object();
    const auto put = [&](const char* name, const std::vector<float>& series) {
      out.set(name, typed_copy("Float32Array", series.data(), series.size()));
    };
    put("time", h.time);
    put("kinetic", h.kinetic);
    put("potential", h.potential);
    put("total", h.total);
    put("momentumX", h.momentum_x);
    put("momentumY", h.momentum_y);
    return out;
  }

  val problem() const {
    const view::Problem& p = session_.problem();
    val out = val::object();
    out.set("kind", std::string(kind_name(p.kind)));
    out.set("headline", p.headline);
    out.set("detail", p.detail);
    out.set("time", p.time);
    out.set("particle", p.particle);
    out.set("quantity", p.quantity);
    return out;
  }

  /// h, and the critical step of the chosen integrator on the scene at rest (null: not
  /// estimated; 0: unstable at every h; Infinity: stable at every h).
  val step_info() {
    const std::optional<double> critical = session_.critical_step();
    val out = val::object();
    out.set("h", session_.parameters().step);
    out.set("integrator", session_.parameters().integrator);
    out.set("critical", critical ? val(*critical) : val::null());
    out.set("estimate", session_.critical_step_is_estimate());
    out.set("note", session_.critical_step_note());
    return out;
  }

  /// "reference" or "student" (yours): whose task code runs.
  void set_code(const std::string& code) {
    session_.set_code(code == "student" ? view::Code::student : view::Code::reference);
  }
  std::string code() const {
    return session_.code() == view::Code::student ? "student" : "reference";
  }
  /// "off", "overlay" or "side-by-side": the reference's run beside yours.
  void set_compare(const std::string& compare) {
    session_.set_compare(compare == "overlay"        ? view::Compare::overlay
                         : compare == "side-by-side" ? view::Compare::side_by_side
                                                     : view::Compare::off);
  }
  std::string compare() const {
    switch (session_.compare()) {
      case view::Compare::overlay:
        return "overlay";
      case view::Compare::side_by_side:
        return "side-by-side";
      case view::Compare::off:
        break;
    }
    return "off";
  }
  /// Your run against the reference's beside it: the figures and the remark; null unless
  /// comparing.
  val comparison() const {
    const std::optional<Comparison> c = session_.comparison();
    if (!c) return val::null();
    val out = val::object();
    out.set("figures", comparison_figures(*c));
    out.set("remark", c->remark);
    out.set("distance", c->distance);
    return out;
  }

  void grab(int particle) { session_.grab(particle); }
  void drag_to(double x, double y) {
    if (std::isfinite(x) && std::isfinite(y)) session_.drag_to(Vec2(x, y));
  }
  void release() { session_.release(); }
  void toggle_pin(int particle) { session_.toggle_pin(particle); }
  void push(int particle, double dvx, double dvy) {
    if (std::isfinite(dvx) && std::isfinite(dvy)) session_.push(particle, Vec2(dvx, dvy));
  }

 private:
  view::Session session_;
};

/// The step of a scene timed in this browser, for the speed figures (viewer/web/README.md): a
/// Simulation of `scene` with `sets` ("KEY=VALUE" lines) for `steps` steps, as springlab-run
/// steps it. Returns the springs, the steps and the seconds; or the kit's message.
val time_steps(const std::string& scene, const std::string& sets, double steps) {
  val out = val::object();
  try {
    SceneParameters p = load_scene(scene);
    std::size_t start = 0;
    while (start < sets.size()) {
      std::size_t end = sets.find('\n', start);
      if (end == std::string::npos) end = sets.size();
      if (end > start) set_assignment(p, std::string_view(sets).substr(start, end - start));
      start = end + 1;
    }
    validate(p);
    Simulation sim(p, reference_implementation());
    const auto begin = std::chrono::steady_clock::now();
    sim.advance(long(steps));
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - begin;
    out.set("springs", double(sim.scene().springs.size()));
    out.set("steps", double(sim.steps_taken()));
    out.set("seconds", took.count());
    out.set("fastForces", sim.fast_forces());
  } catch (const std::exception& error) {
    out.set("error", std::string(error.what()));
  }
  return out;
}

val scene_names() {
  return text_list(task_scene_names());
}
val integrator_list() {
  return text_list(integrator_names());
}
bool reference_here() {
  return reference_is_available();
}

}  // namespace springlab::web

EMSCRIPTEN_BINDINGS(springlab) {
  using springlab::web::Lab;
  emscripten::class_<Lab>("Lab")
      .constructor<std::string>()
      .function("load", &Lab::load)
      .function("loadText", &Lab::load_text)
      .function("source", &Lab::source)
      .function("fields", &Lab::fields)
      .function("set", &Lab::set)
      .function("reset", &Lab::reset)
      .function("running", &Lab::running)
      .function("setRunning", &Lab::set_running)
      .function("frame", &Lab::frame)
      .function("droppedSteps", &Lab::dropped_steps)
      .function("singleStep", &Lab::single_step)
      .function("advance", &Lab::advance)
      .function("setRealTimeFactor", &Lab::set_real_time_factor)
      .function("state", &Lab::state)
      .function("positions", &Lab::positions)
      .function("velocities", &Lab::velocities)
      .function("pinned", &Lab::pinned)
      .function("springs", &Lab::springs)
      .function("history", &Lab::history)
      .function("problem", &Lab::problem)
      .function("stepInfo", &Lab::step_info)
      .function("setCode", &Lab::set_code)
      .function("code", &Lab::code)
      .function("setCompare", &Lab::set_compare)
      .function("compare", &Lab::compare)
      .function("comparison", &Lab::comparison)
      .function("grab", &Lab::grab)
      .function("dragTo", &Lab::drag_to)
      .function("release", &Lab::release)
      .function("togglePin", &Lab::toggle_pin)
      .function("push", &Lab::push);
  emscripten::function("timeSteps", &springlab::web::time_steps);
  emscripten::function("sceneNames", &springlab::web::scene_names);
  emscripten::function("integratorNames", &springlab::web::integrator_list);
  emscripten::function("referenceAvailable", &springlab::web::reference_here);
}
