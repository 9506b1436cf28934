// The viewer as a user meets it, in a real window (under Xvfb in CI): what is drawn is where the
// simulation says, the panel answers real (synthetic) mouse input, switching anything does not
// crash, a divergence and unwritten student code each show their banner.
#include "gui/app.hpp"
#include "gui/runs.hpp"
#include "gui/scene_drawing.hpp"
#include "gui/sfml_compat.hpp"
#include "lab_catch.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/implementation.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace springlab;
using namespace springlab::view;
using compat::Input;
using lab_catch::Approx;
using lab_catch::Contains;
using lab_catch::StartsWith;
using lab_catch::WithinRel;

AppOptions options_for(const std::string& scene) {
  AppOptions options;
  options.scene = scene;
  options.frame_rate_limit = false;
  options.fixed_frame_time = true;
  return options;
}

sf::Event mouse_moved(sf::Vector2f at) {
  Input input;
  input.kind = Input::Kind::mouse_moved;
  input.position = {int(at.x), int(at.y)};
  return compat::event_of(input);
}

sf::Event mouse_button(bool pressed, sf::Mouse::Button button, sf::Vector2f at) {
  Input input;
  input.kind = pressed ? Input::Kind::button_pressed : Input::Kind::button_released;
  input.button = button;
  input.position = {int(at.x), int(at.y)};
  return compat::event_of(input);
}

sf::Event wheel_turned(float notches, sf::Vector2f at) {
  Input input;
  input.kind = Input::Kind::wheel;
  input.delta = notches;
  input.position = {int(at.x), int(at.y)};
  return compat::event_of(input);
}

sf::Event key(bool pressed, sf::Keyboard::Key code, bool shift = false) {
  Input input;
  input.kind = pressed ? Input::Kind::key_pressed : Input::Kind::key_released;
  input.key = code;
  input.shift = shift;
  return compat::event_of(input);
}

sf::Event typed(char32_t character) {
  Input input;
  input.kind = Input::Kind::text;
  input.character = character;
  return compat::event_of(input);
}

// Moves there, presses, releases: a frame after each, as a hand would.
void click(App& app, sf::Vector2f at, sf::Mouse::Button button = sf::Mouse::Button::Left) {
  app.handle(mouse_moved(at));
  app.frame();
  app.handle(mouse_button(true, button, at));
  app.frame();
  app.handle(mouse_button(false, button, at));
  app.frame();
}

void drag(App& app, sf::Vector2f from, sf::Vector2f to) {
  app.handle(mouse_moved(from));
  app.frame();
  app.handle(mouse_button(true, sf::Mouse::Button::Left, from));
  app.frame();
  for (int k = 1; k <= 4; ++k) {
    app.handle(mouse_moved(from + (to - from) * (float(k) / 4)));
    app.frame();
  }
  app.handle(mouse_button(false, sf::Mouse::Button::Left, to));
  app.frame();
}

sf::Vector2f centre_of(const WidgetRect& r) {
  return {(r.left + r.right) / 2, (r.top + r.bottom) / 2};
}

sf::Color pixel_at(const sf::Image& image, sf::Vector2f at) {
  const long x = std::lround(at.x), y = std::lround(at.y);
  REQUIRE((x >= 0 && y >= 0 && x < long(image.getSize().x) && y < long(image.getSize().y)));
  return compat::pixel(image, unsigned(x), unsigned(y));
}

std::string text(sf::Color c) {
  return "(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + ")";
}

// Screenshots of the tests, for a person to look at when one fails.
std::string shot(const std::string& name) {
  std::filesystem::create_directories("viewer-screenshots");
  return "viewer-screenshots/" + name + ".png";
}

void keep_shot(const sf::Image& image, const std::string& name) {
  if (!image.saveToFile(shot(name))) WARN("could not save " << shot(name));
}

}  // namespace

TEST_CASE("each particle is drawn at the screen position of its simulated position",
          "[viewer][draw]") {
  App app(options_for("task4"));
  for (int k = 0; k < 30; ++k)
    app.frame();  // in motion: not at the grid positions any more
  // Pin a corner with a right-click on it, to see the pinned mark too.
  const Simulation& before = *app.session().primary();
  click(app, app.camera().to_screen(before.particles().position.col(0)), sf::Mouse::Button::Right);
  REQUIRE(app.session().pinned(0));
  app.handle(mouse_moved({5, 5}));  // away from the particles: no highlight
  app.frame(true);
  keep_shot(app.captured(), "draw");
  const Simulation& sim = *app.session().primary();
  const Particles& p = sim.particles();
  REQUIRE(p.position.col(8) != grid_position(2, 2, 1.0));
  for (int i = 0; i < p.size(); ++i) {
    const sf::Vector2f at = app.camera().to_screen(p.position.col(i));
    INFO("particle " << i << " at (" << at.x << ", " << at.y << ") px");
    REQUIRE(app.camera().viewport().contains(at));
    const sf::Color want = p.pinned[std::size_t(i)] ? colour::pinned : colour::particle;
    CHECK(text(pixel_at(app.captured(), at)) == text(want));
  }
  // The particle under the mouse is ringed and shows its forces as arrows.
  app.handle(mouse_moved(app.camera().to_screen(p.position.col(8))));
  app.frame();
  app.frame(true);
  keep_shot(app.captured(), "force-arrows");
  CHECK(app.last_frame().hovered == 8);
  // Far from the grid: the background.
  const Viewport& area = app.camera().viewport();
  const sf::Vector2f far(area.left + area.width - 5, area.top + area.height / 2);
  CHECK(text(pixel_at(app.captured(), far)) == text(colour::background));
}

TEST_CASE(
    "the default view follows the fabric as it sags, clear of the plots, until the user "
    "zooms",
    "[viewer][draw]") {
  App app(options_for("task5"));
  const auto all_in_view = [&app] {
    const Particles& p = app.session().primary()->particles();
    const double margin = app.camera().pixels_per_metre() * 0.5;  // half a spacing, px
    const Viewport& area = app.camera().viewport();
    for (int i = 0; i < p.size(); ++i) {
      const sf::Vector2f at = app.camera().to_screen(p.position.col(i));
      if (at.x < area.left + margin || at.x > area.left + area.width - margin ||
          at.y < area.top + margin || at.y > area.top + area.height - margin)
        return false;
    }
    return true;
  };
  const double fitted = app.camera().pixels_per_metre();
  for (int frame = 0; frame < 120; ++frame) {  // 2 s: the fabric has sagged past its start
    app.frame();
    INFO("frame " << frame);
    REQUIRE(all_in_view());
  }
  CHECK(app.camera().pixels_per_metre() < fitted);  // it did have to zoom out
  // Zoomed in by hand: the view stays where the user put it.
  app.handle(mouse_moved(app.camera().viewport().centre()));
  app.frame();
  app.handle(wheel_turned(15, app.camera().viewport().centre()));
  const double zoomed = app.camera().pixels_per_metre();
  for (int frame = 0; frame < 30; ++frame)
    app.frame();
  CHECK(app.camera().pixels_per_metre() == zoomed);
  CHECK_FALSE(all_in_view());
}

TEST_CASE("the panel, the plots, the scene's label and the summary show one time and one energy",
          "[viewer][draw]") {
  // Each frame steps first and then draws: what the panel, the plots and the label read is the
  // same state. Task 5 has gravity, whose energy counts in the potential of plots and summary.
  App app(options_for("task5"));
  app.session().parameters().rows = app.session().parameters().cols = 6;
  app.session().apply();
  for (int k = 0; k < 12; ++k) {
    app.frame();
    const Session& session = app.session();
    const History& h = session.history();
    CAPTURE(k, app.last_frame().steps, session.time(), app.panel().shown_time(), app.label_time());
    REQUIRE(!h.time.empty());
    CHECK(app.panel().shown_time() == session.time());
    CHECK(app.label_time() == session.time());
    // The plots' last point, as drawn and as kept.
    CHECK(app.panel().shown_plot_time() == double(float(session.time())));
    CHECK(h.time.back() == float(session.time()));
  }
  REQUIRE(app.session().time() > 0.0);
  const Diagnostics d = app.session().primary()->diagnostics();
  const History& h = app.session().history();
  REQUIRE(d.gravitational != 0.0);  // it fell
  CHECK(h.kinetic.back() == float(d.kinetic));
  CHECK(h.potential.back() == float(d.potential + d.gravitational));
  CHECK(h.total.back() == float(d.total()));
  // The summary printed on stdout: the same t and energies (6 significant digits).
  std::ostringstream out;
  print_summary(app.session(), out);
  const std::string text = out.str();
  INFO(text);
  // "t = T s; energy E J (kinetic K, potential P (springs S, gravity G))", read without
  // <regex> (GCC 12 warns inside it under the sanitizers' -O1).
  const auto after = [&text](const std::string& label) {
    const auto at = text.find(label);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + label.size()));
  };
  CHECK_THAT(after("t = "), WithinRel(app.session().time(), 1e-5));
  CHECK_THAT(after("; energy "), WithinRel(double(h.total.back()), 1e-5));
  CHECK_THAT(after("(kinetic "), WithinRel(double(h.kinetic.back()), 1e-5));
  CHECK_THAT(after(", potential "), WithinRel(double(h.potential.back()), 1e-5));
  CHECK_THAT(after(", gravity "), WithinRel(d.gravitational, 1e-5));
}

TEST_CASE("the panel says whether its critical step is the limit or a safe step from a bound",
          "[viewer][draw]") {
  // Up to 100 particles an eigen-solve gives the limit; above, the bound on omega_max gives a
  // step below it (handout section 5: 0.067 s on the 20x20 fabric, whose limit is 0.084 s).
  Session small("task4"), large("task5");
  REQUIRE(small.critical_step().has_value());
  REQUIRE(large.critical_step().has_value());
  CHECK_FALSE(small.critical_step_is_estimate());
  CHECK(large.critical_step_is_estimate());
  const double exact =
      verlet_critical_step(linearise_at_rest(large.parameters(), reference_implementation()));
  CAPTURE(*large.critical_step(), exact);
  CHECK(*large.critical_step() < exact);
}

TEST_CASE("switching scenes, code, integrators, comparison and grid size never crashes",
          "[viewer][switch]") {
  App app(options_for("task1"));
  for (const std::string& scene : task_scene_names()) {
    app.session().load(scene);
    for (Code code : {Code::reference, Code::student})
      for (Compare compare : {Compare::off, Compare::overlay, Compare::side_by_side})
        for (const std::string& integrator : integrator_names()) {
          INFO(scene << ", " << (code == Code::student ? "student" : "reference") << ", "
                     << integrator << ", compare " << int(compare));
          app.session().set_code(code);
          app.session().set_compare(compare);
          app.session().parameters().integrator = integrator;
          app.session().apply();
          for (int k = 0; k < 3; ++k)
            app.frame();
          const Problem::Kind kind = app.session().problem().kind;
          if (code == Code::reference) CHECK(app.session().primary() != nullptr);
          CHECK((kind == Problem::Kind::none || kind == Problem::Kind::diverged ||
                 (code == Code::student && kind == Problem::Kind::not_implemented)));
        }
  }
  app.session().set_code(Code::reference);
  for (int side : {2, 12, 1, 40}) {  // task4 moves particle 8: a 2x2 grid keeps it inside
    app.session().parameters().rows = app.session().parameters().cols = side;
    app.session().apply();
    app.frame();
    INFO("grid " << side << "x" << side);
    if (side == 1) {  // a single particle is refused with a message, not a crash
      CHECK(app.session().problem().kind == Problem::Kind::invalid);
      CHECK(app.panel().banner_shown());
    } else {
      REQUIRE(app.session().primary() != nullptr);
      CHECK(app.session().primary()->particles().size() == side * side);
      CHECK(app.session().running());  // also after the refused size
    }
  }
  Input resized;
  resized.kind = Input::Kind::resized;
  resized.size = {900, 600};
  app.window().setSize({900, 600});
  app.handle(compat::event_of(resized));
  app.frame(true);
  keep_shot(app.captured(), "switch");
  CHECK(app.camera().viewport().width == Approx(900 - Panel::width));
}

TEST_CASE("a divergence pauses the run and shows when, where and why, with a reset",
          "[viewer][divergence]") {
  App app(options_for("task1"));
  app.session().parameters().step = 0.5;  // a hundred times explicit Euler's limit here
  app.session().reset();
  for (int k = 0; k < 600 && app.session().problem().kind == Problem::Kind::none; ++k)
    app.frame();
  const Problem& problem = app.session().problem();
  REQUIRE(problem.kind == Problem::Kind::diverged);
  CHECK(problem.time > 0);
  CHECK(problem.particle >= 0);
  CHECK_THAT(problem.headline, StartsWith("The simulation diverged at t = "));
  CHECK_THAT(problem.detail,
             Contains("times the critical step") && Contains("of explicit Euler on this scene"));
  CHECK_FALSE(app.session().running());
  const double stopped = app.session().time();
  app.frame();  // ImGui sizes a new window in its first frame and draws it from the second
  app.frame(true);
  keep_shot(app.captured(), "divergence");
  CHECK(app.session().time() == stopped);  // paused
  REQUIRE(app.panel().banner_shown());
  const WidgetRect banner = *app.panel().rect("banner");
  const sf::Color inside = pixel_at(app.captured(), {banner.left + 4, banner.top + 4});
  INFO("banner pixel " << text(inside));
  CHECK((inside.r > 100 && inside.g < 60 && inside.b < 60));  // the banner's red

  click(app, centre_of(*app.panel().rect("banner reset")));
  CHECK(app.session().problem().kind == Problem::Kind::none);
  CHECK(app.session().running());
  app.frame();
  CHECK_FALSE(app.panel().banner_shown());
}

TEST_CASE("a click and drag on a slider changes the scene's parameter", "[viewer][input]") {
  App app(options_for("task4"));
  app.frame();
  const auto slider = app.panel().rect("structural.k");
  REQUIRE(slider);
  INFO("slider at " << slider->left << ".." << slider->right << ", " << slider->top);
  REQUIRE(slider->bottom < float(app.window().getSize().y));
  const float y = (slider->top + slider->bottom) / 2;
  const float width = slider->right - slider->left;
  drag(app, {slider->left + 0.5f * width, y}, {slider->left + 0.8f * width, y});
  const double k = app.session().parameters().structural.k;
  CHECK(k > 20.0);
  // The running simulation uses it at once, without a reset.
  REQUIRE(app.session().primary() != nullptr);
  CHECK(app.session().primary()->scene().springs.front().k == k);
  CHECK(app.session().time() > 0.1);
}

TEST_CASE("a particle dragged with the mouse follows it, and is let go where it is dropped",
          "[viewer][input]") {
  App app(options_for("task4"));
  app.frame();
  const Vec2 start = app.session().primary()->particles().position.col(4);
  const sf::Vector2f from = app.camera().to_screen(start);
  // Mouse events carry whole pixels.
  const sf::Vector2f to(std::round(from.x) + 60, std::round(from.y) - 40);
  app.handle(mouse_moved(from));
  app.frame();
  app.handle(mouse_button(true, sf::Mouse::Button::Left, from));
  app.frame();
  app.handle(mouse_moved(to));
  for (int k = 0; k < 10; ++k)
    app.frame();  // held there while the rest moves
  const Vec2 held = app.session().primary()->particles().position.col(4);
  CHECK((held - app.camera().to_world(to)).norm() < 1e-9);
  const Vec2 velocity = app.session().primary()->particles().velocity.col(4);
  CAPTURE(velocity.x(), velocity.y());
  CHECK(velocity.norm() < 1e-12);  // Verlet's (4.4) rounds 3r - 4r + r to ~1e-17, not 0
  app.handle(mouse_button(false, sf::Mouse::Button::Left, to));
  for (int k = 0; k < 10; ++k)
    app.frame();
  CHECK_FALSE(app.session().pinned(4));
  CHECK((app.session().primary()->particles().position.col(4) - held).norm() > 1e-6);
}

TEST_CASE("the student's unwritten task shows its message, and the reference is one click away",
          "[viewer][student]") {
  for (const std::string& scene : task_scene_names()) {
    App app(options_for(scene));
    app.session().set_code(Code::student);
    // Five frames, and more until the first step has run (task4-damped's h = 0.085 s is five
    // frames of 1/60 s).
    for (int k = 0; k < 5 || (k < 60 && app.session().problem().kind == Problem::Kind::none); ++k)
      app.frame();
    const int task = app.session().task();
    INFO(scene);
    const Problem& problem = app.session().problem();
    REQUIRE(problem.kind == Problem::Kind::not_implemented);
    CHECK(problem.headline == "Task " + std::to_string(task) +
                                  " is not implemented yet \u2014 see handout section " +
                                  std::to_string(task));
    CHECK_THAT(problem.detail, Contains("tasks/task" + std::to_string(task)));
    app.frame(true);
    CHECK(app.panel().banner_shown());
    if (task == 2) keep_shot(app.captured(), "student-task2");
    // The comparison mode with the unwritten code says the same, and does not crash either.
    app.session().set_compare(Compare::side_by_side);
    app.session().set_running(true);
    app.frame();
    for (int k = 0; k < 60 && app.session().problem().kind == Problem::Kind::none; ++k)
      app.frame();  // at least one step (task4-damped)
    CHECK(app.session().problem().kind == Problem::Kind::not_implemented);
  }
}

TEST_CASE("side by side and overlaid, the student's run and the reference are both drawn",
          "[viewer][compare]") {
  App app(options_for("task4"));
  // The reference stands in for finished student code: the two runs must then agree exactly.
  app.session().student_code = [](int) -> const Implementation& {
    return reference_implementation();
  };
  app.session().set_compare(Compare::side_by_side);
  CHECK(app.session().reference() == nullptr);  // only the student's code is compared
  app.session().set_code(Code::student);
  REQUIRE(app.session().reference() != nullptr);
  for (int k = 0; k < 20; ++k)
    app.frame();
  app.frame(true);
  keep_shot(app.captured(), "compare-side-by-side");
  CHECK(app.session().largest_difference() == 0.0);
  CHECK(app.camera(1).viewport().left == Approx(app.camera(0).viewport().width));
  for (int view : {0, 1}) {
    const Simulation& sim = view == 0 ? *app.session().primary() : *app.session().reference();
    for (int i = 0; i < sim.particles().size(); ++i) {
      const sf::Vector2f at = app.camera(view).to_screen(sim.particles().position.col(i));
      INFO("view " << view << ", particle " << i);
      CHECK(app.camera(view).viewport().contains(at));
      CHECK(text(pixel_at(app.captured(), at)) == text(colour::particle));
    }
  }
  app.session().set_compare(Compare::overlay);
  for (int k = 0; k < 5; ++k)
    app.frame();
  app.frame(true);
  keep_shot(app.captured(), "compare-overlay");
  CHECK(app.session().reference() != nullptr);
  CHECK(app.session().problem().kind == Problem::Kind::none);
}

TEST_CASE("the keyboard and the wheel reach the panel and the view", "[viewer][keys]") {
  App app(options_for("task4"));
  app.frame();
  // Type a scene file's path into the panel and load it.
  const std::string path = std::filesystem::absolute(shot("wide")).replace_extension(".toml");
  std::ofstream(path) << "name = \"wide\"\ntask = 3\nrows = 2\ncols = 5\nshear.enabled = true\n";
  click(app, centre_of(*app.panel().rect("scene file")));
  for (char c : path)
    app.handle(typed(char32_t(static_cast<unsigned char>(c))));
  app.frame();
  click(app, centre_of(*app.panel().rect("load")));
  CHECK(app.session().source() == path);
  CHECK(app.session().parameters().name == "wide");
  REQUIRE(app.session().primary() != nullptr);
  CHECK(app.session().primary()->particles().size() == 10);

  // Space pauses (once the text field has let the keyboard go), the wheel zooms.
  click(app, app.camera().viewport().centre() + sf::Vector2f(0, 250));
  app.handle(key(true, sf::Keyboard::Key::Space));
  app.frame();
  CHECK_FALSE(app.session().running());
  const double scale = app.camera().pixels_per_metre();
  app.handle(mouse_moved({300, 300}));
  app.handle(wheel_turned(2.0f, {300, 300}));
  app.frame();
  CHECK(app.camera().pixels_per_metre() > scale);

  // Shift+click pushes the particle under the mouse by the panel's push velocity.
  const sf::Vector2f at =
      app.camera().to_screen(app.session().primary()->particles().position.col(0));
  const Vec2 before = app.session().primary()->particles().velocity.col(0);
  app.handle(key(true, sf::Keyboard::Key::LShift, true));
  click(app, {std::round(at.x), std::round(at.y)});
  const Vec2 v = app.session().primary()->particles().velocity.col(0);
  CHECK((v - before - app.settings().push_velocity).norm() < 1e-12);
}

// What the glue between SFML and ImGui must do alike on every ImGui version (1.86 reads its
// input from arrays, 1.87 and later from queued events).
TEST_CASE("a press and its release within one frame still click a button", "[viewer][keys]") {
  // A quick click on a slow frame: both events come before the next frame.
  App app(options_for("task4"));
  app.session().set_running(false);
  app.frame();
  const sf::Vector2f at = centre_of(*app.panel().rect("step once"));
  app.handle(mouse_moved(at));
  app.frame();
  app.handle(mouse_button(true, sf::Mouse::Button::Left, at));
  app.handle(mouse_button(false, sf::Mouse::Button::Left, at));
  for (int k = 0; k < 3; ++k)
    app.frame();
  CHECK(app.session().primary()->steps_taken() == 1);
}

TEST_CASE("backspace deletes in the panel's text field", "[viewer][keys]") {
  App app(options_for("task4"));
  app.frame();
  click(app, centre_of(*app.panel().rect("scene file")));
  for (char c : std::string("task1x"))
    app.handle(typed(char32_t(c)));
  app.frame();
  app.handle(key(true, sf::Keyboard::Key::Backspace));
  app.frame();
  app.handle(key(false, sf::Keyboard::Key::Backspace));
  app.frame();
  click(app, centre_of(*app.panel().rect("load")));
  CHECK(app.session().source() == "task1");
}

TEST_CASE("a grid too large for OpenGL lines is drawn in memory, each particle where it is",
          "[viewer][draw]") {
  App app(options_for("task2"));
  app.session().parameters().rows = app.session().parameters().cols = 70;  // 9,660 springs
  app.session().apply();
  for (int k = 0; k < 10; ++k)
    app.frame();
  app.frame(true);
  keep_shot(app.captured(), "draw-large");
  const Simulation& sim = *app.session().primary();
  REQUIRE(sim.scene().springs.size() > 5000);
  int wrong = 0;
  for (int i = 0; i < sim.particles().size(); ++i) {
    const sf::Vector2f at = app.camera().to_screen(sim.particles().position.col(i));
    if (pixel_at(app.captured(), at) != colour::particle) ++wrong;
  }
  CHECK(wrong == 0);
}

// Issue 14: a level of detail. What is drawn is counted (DrawCounts), never timed.
TEST_CASE("a 200x200 fabric in the default window is drawn as a surface, a 4x4 grid as springs",
          "[viewer][detail]") {
  App app(options_for("task5"));
  SceneParameters& p = app.session().parameters();
  p.rows = p.cols = 200;
  app.session().apply();
  app.session().set_running(false);  // at rest: every spring at its rest length
  app.frame();
  app.frame(true);
  keep_shot(app.captured(), "surface-200");
  const double pixels = p.spacing * app.camera().pixels_per_metre();
  const int stride = surface_stride(p, app.camera());
  CAPTURE(pixels, stride);
  REQUIRE(pixels < surface_below_pixels);  // the default window shows 200 spacings in ~420 px
  const DrawCounts& drawn = app.last_frame().drawn;
  CHECK(drawn.surface);
  CHECK(drawn.springs == 0);
  // Cells of at least surface_cell_pixels: every stride-th grid line, and the last.
  CHECK(stride * pixels >= surface_cell_pixels);
  CHECK((stride - 1) * pixels < surface_cell_pixels);
  const long lines = (199 + stride - 1) / stride + 1;
  CHECK(drawn.triangles == 2 * (lines - 1) * (lines - 1));
  CHECK(drawn.dots == 200);  // the pinned top row, still marked
  // The surface has the springs' colour scale: the cloth at rest is drawn at_rest.
  const Simulation& sim = *app.session().primary();
  const sf::Vector2f middle = app.camera().to_screen(sim.particles().position.col(100 * 200 + 100));
  CHECK(text(pixel_at(app.captured(), middle)) == text(colour::at_rest));

  // Zoomed in until a spacing spans surface_below_pixels or more: the springs again.
  const sf::Vector2f centre = app.camera().viewport().centre();
  app.handle(mouse_moved(centre));
  for (int k = 0; k < 10 && p.spacing * app.camera().pixels_per_metre() < surface_below_pixels; ++k)
    app.handle(wheel_turned(3.0f, centre));
  app.frame();
  CHECK_FALSE(app.last_frame().drawn.surface);
  CHECK(app.last_frame().drawn.springs > 0);
  CHECK(app.last_frame().drawn.triangles == 0);

  p.rows = p.cols = 4;
  app.session().apply();
  app.frame();
  app.frame();
  const DrawCounts& small = app.last_frame().drawn;
  CHECK_FALSE(small.surface);
  CHECK(small.triangles == 0);
  CHECK(small.springs == long(app.session().primary()->scene().springs.size()));
  CHECK(small.dots == 16);
}

namespace {

// A run's state after 40 frames of 1/60 s with edits between them, as a hand would make them.
struct Ran {
  Vectors position, velocity;
  double time = 0.0;
  std::vector<float> energy;
  std::vector<bool> pinned;
};

Ran run_with_edits(Stepping stepping) {
  AppOptions options = options_for("task5");
  options.stepping = stepping;
  App app(options);
  CHECK(app.stepping_thread() == (stepping == Stepping::thread));
  SceneParameters& p = app.session().parameters();
  p.rows = p.cols = 30;
  app.session().apply();
  for (int k = 0; k < 40; ++k) {
    if (k == 10) app.session().toggle_pin(31);
    if (k == 15) app.session().push(400, Vec2(0.5, 1.0));
    if (k == 20) {
      app.session().parameters().structural.k = 35.0;
      app.session().apply();  // a new k mid-motion
    }
    if (k == 25) app.session().grab(899);
    if (k >= 25 && k < 30) app.session().drag_to(Vec2(40.0 + k, -20.0));
    if (k == 30) app.session().release();
    app.frame();
  }
  const Simulation& sim = *app.session().primary();  // session() waits for the thread
  return {sim.particles().position, sim.particles().velocity, sim.time(),
          app.session().history().total, sim.particles().pinned};
}

}  // namespace

TEST_CASE("the stepping thread gives the same run as stepping in the window's thread",
          "[viewer][thread]") {
  // Headless frames of exactly 1/60 s take the same steps in both: the thread changes where
  // they are taken, not which, and the edits reach the simulation between the same steps.
  const Ran alone = run_with_edits(Stepping::synchronous);
  const Ran threaded = run_with_edits(Stepping::thread);
  CHECK(threaded.time == alone.time);
  CHECK(alone.time > 0.6);
  CHECK(threaded.pinned == alone.pinned);
  CHECK(threaded.energy == alone.energy);
  CHECK((threaded.position - alone.position).cwiseAbs().maxCoeff() == 0.0);
  CHECK((threaded.velocity - alone.velocity).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("with a stepping thread, a dragged particle follows the mouse and the panel edits",
          "[viewer][thread]") {
  AppOptions options = options_for("task4");
  options.stepping = Stepping::thread;
  App app(options);
  app.frame();
  const Vec2 start = app.session().primary()->particles().position.col(4);
  const sf::Vector2f from = app.camera().to_screen(start);
  const sf::Vector2f to(std::round(from.x) + 60, std::round(from.y) - 40);
  drag(app, from, to);
  // Let go where it was dropped: it moved with the mouse, and is free again.
  CHECK_FALSE(app.session().pinned(4));
  CHECK((app.session().primary()->particles().position.col(4) - start).norm() > 0.1);
  // The panel's Reset button, clicked while the thread steps, starts the scene afresh.
  for (int k = 0; k < 10; ++k)
    app.frame();
  REQUIRE(app.session().time() > 0.1);
  click(app, centre_of(*app.panel().rect("reset")));
  CHECK(app.session().time() < 0.1);
  CHECK(app.session().running());
}
