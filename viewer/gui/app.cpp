#include "gui/app.hpp"

#include "gui/resident_driver.hpp"
#include "gui/scene_drawing.hpp"

#include <imgui.h>

#include <SFML/Graphics/Texture.hpp>
#include <SFML/Graphics/View.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace springlab::view {
namespace {

// A "1 m"-style scale bar: the largest 1, 2 or 5 × 10^k metres under 120 pixels.
double scale_bar_metres(double pixels_per_metre) {
  const double most = 120.0 / pixels_per_metre;
  const double power = std::pow(10.0, std::floor(std::log10(most)));
  for (double step : {5.0, 2.0, 1.0})
    if (step * power <= most) return step * power;
  return power;
}

}  // namespace

App::App(const AppOptions& options)
    : options_(options),
      // SFML's default context has no antialiasing: identical pixels on every machine, and cheap
      // in software.
      window_(compat::video_mode({options.width, options.height}), "springlab viewer"),
      glue_(window_),
      session_(options.scene) {
  const bool thread = options.stepping == Stepping::thread ||
                      (options.stepping == Stepping::automatic && !options.fixed_frame_time);
  if (thread) stepper_ = std::make_unique<Stepper>();
  if (options.frame_rate_limit) window_.setFramerateLimit(60);
  keep_gl_driver_loaded();
  layout();
}

int App::views() const {
  return session_.compare() == Compare::side_by_side && session_.reference() ? 2 : 1;
}

const Simulation* App::simulation_of(int view) const {
  return view == 0 ? session_.primary() : session_.reference();
}

void App::layout() {
  const sf::Vector2u size = window_.getSize();
  const float width = std::max(float(size.x) - Panel::width, 100.0f) / float(views());
  const float height = std::max(float(size.y) - Panel::plot_height, 100.0f);
  for (int v = 0; v < 2; ++v)
    cameras_[std::size_t(v)].set_viewport({float(v) * width, 0.0f, width, height});
}

void App::fit() {
  finish_stepping();  // reads the particles
  layout();
  for (int v = 0; v < views(); ++v)
    if (const Simulation* sim = simulation_of(v))
      cameras_[std::size_t(v)].fit(sim->particles().position, sim->parameters().spacing);
}

int App::view_at(sf::Vector2f point) const {
  for (int v = 0; v < views(); ++v)
    if (cameras_[std::size_t(v)].viewport().contains(point)) return v;
  return -1;
}

int App::hovered() const {
  const int view = view_at(mouse_);
  const Simulation* sim = view >= 0 ? simulation_of(view) : nullptr;
  if (!sim || glue_.wants_mouse()) return -1;
  return particle_at(*sim, cameras_[std::size_t(view)], mouse_);
}

void App::finish_stepping() {
  if (stepper_) stepper_->wait();
}

void App::handle(const sf::Event& event) {
  using Kind = compat::Input::Kind;
  finish_stepping();  // an event may edit the session or read its particles
  const compat::Input input = compat::read(event);
  glue_.handle(input);
  const bool shift_key =
      input.key == sf::Keyboard::Key::LShift || input.key == sf::Keyboard::Key::RShift;
  switch (input.kind) {
    case Kind::closed:
      window_.close();
      break;
    case Kind::resized:
      window_.setView(sf::View(compat::float_rect(0, 0, float(input.size.x), float(input.size.y))));
      fit();
      break;
    case Kind::mouse_moved: {
      const sf::Vector2f now(float(input.position.x), float(input.position.y));
      if (session_.grabbed() >= 0 && view_at(now) >= 0)
        session_.drag_to(cameras_[std::size_t(view_at(now))].to_world(now));
      else if (panning_)
        for (Camera& camera : cameras_)
          camera.pan(now - mouse_);
      mouse_ = now;
      break;
    }
    case Kind::button_pressed:
      mouse_ = sf::Vector2f(float(input.position.x), float(input.position.y));
      if (!glue_.wants_mouse()) on_press(input.button);
      break;
    case Kind::button_released:
      if (input.button == sf::Mouse::Button::Left) {
        session_.release();
        panning_ = false;
      }
      break;
    case Kind::wheel:
      if (!glue_.wants_mouse() && view_at(mouse_) >= 0)
        for (Camera& camera : cameras_)
          camera.zoom(std::pow(1.15, double(input.delta)), mouse_);
      break;
    case Kind::key_pressed:
      if (shift_key)
        shift_ = true;
      else if (!glue_.wants_keyboard())
        on_key(input.key);
      break;
    case Kind::key_released:
      if (shift_key) shift_ = false;
      break;
    default:
      break;
  }
}

void App::on_press(sf::Mouse::Button button) {
  const int view = view_at(mouse_);
  const Simulation* sim = view >= 0 ? simulation_of(view) : nullptr;
  if (!sim) return;
  const Camera& camera = cameras_[std::size_t(view)];
  const int particle = particle_at(*sim, camera, mouse_);
  if (particle >= 0) settings_.selected = particle;
  if (button == sf::Mouse::Button::Right && particle >= 0) {
    session_.toggle_pin(particle);
  } else if (button == sf::Mouse::Button::Left && particle >= 0 && shift_) {
    session_.push(particle, settings_.push_velocity);
  } else if (button == sf::Mouse::Button::Left && particle >= 0) {
    session_.grab(particle);
    session_.drag_to(camera.to_world(mouse_));
  } else if (button == sf::Mouse::Button::Left) {
    panning_ = true;
  }
}

void App::on_key(sf::Keyboard::Key key) {
  switch (key) {
    case sf::Keyboard::Key::Space:
      session_.set_running(!session_.running());
      break;
    case sf::Keyboard::Key::S:
    case sf::Keyboard::Key::Right:
      session_.single_step();
      break;
    case sf::Keyboard::Key::R:
      session_.reset();
      break;
    case sf::Keyboard::Key::F:
      fit();
      break;
    default:
      break;
  }
}

void App::frame(bool capture) {
  using Clock = std::chrono::steady_clock;
  auto mark = Clock::now();
  // The seconds since the last mark, which moves to now.
  const auto lap = [&mark] {
    const auto now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - mark).count();
    mark = now;
    return seconds;
  };
  FramePhases phases;
  finish_stepping();  // the session is the window's again until this frame's steps start
  const double waited = lap();
  if (stepper_) {
    phases.thread = info_.stepping_seconds = take_stepping_seconds();
    if (launched_steps_ > 0) {
      const double each = phases.thread / double(launched_steps_);
      step_seconds_ = step_seconds_ > 0.0 ? 0.8 * step_seconds_ + 0.2 * each : each;
    }
    launched_steps_ = 0;
  }
  while (const std::optional<sf::Event> event = compat::poll(window_))
    handle(*event);
  if (!window_.isOpen()) return;
  info_.frame_seconds = clock_.restart().asSeconds();
  glue_.new_frame(options_.fixed_frame_time ? 1.0f / 60.0f : float(info_.frame_seconds));
  layout();
  info_.hovered = hovered();
  const double events = lap();
  const double simulated = options_.fixed_frame_time ? 1.0 / 60.0 : info_.frame_seconds;
  if (!stepper_) {
    // Step first: the panel, the plots, the labels and the scene then all show the state after
    // this frame's steps (one time, one set of energies), and a click in the panel shows at once.
    info_.steps = session_.frame(simulated);
    info_.stepping_seconds = phases.stepping = lap();
  }
  Viewport scene_area = cameras_[0].viewport();
  scene_area.width *= float(views());
  const PanelRequests requests = panel_.draw(session_, settings_, info_, scene_area);
  layout();  // the panel may have switched the comparison on or off
  if (requests.fit || fitted_to_ != session_.fresh_starts()) {
    fit();
    fitted_to_ = session_.fresh_starts();
  }
  plan_drawing();
  phases.panel = events + lap();
  if (stepper_) {
    // From here on the window reads only its copy (plan_) until finish_stepping().
    const long steps = info_.steps = session_.steps_due(simulated, most_steps());
    info_.dropped_steps = session_.dropped_steps();
    if (steps > 0) stepper_->start([this, steps] { session_.advance(steps); });
    launched_steps_ = steps;
    phases.stepping = waited + lap();
  }
  draw_scenes();
  phases.scene = lap();
  draw_labels();
  glue_.render();
  phases.imgui = lap();
  if (capture) {
    sf::Texture texture;
    if (compat::resize(texture, window_.getSize())) {
      texture.update(window_);
      captured_ = texture.copyToImage();
    } else {
      captured_ = sf::Image();
    }
  }
  window_.display();
  phases.display = lap();
  info_.phases = phases;
}

// With a stepping thread in real time, a frame takes no more steps than the thread can take in
// 90 % of a frame at 60 frames/s (at least one): a scene that steps slower than real time then
// runs slower, at 60 frames/s, rather than at a few frames a second that each wait for a tenth
// of a second's steps. Headless runs with a fixed frame time take every step.
long App::most_steps() const {
  if (options_.fixed_frame_time || !(step_seconds_ > 0.0)) return std::numeric_limits<long>::max();
  const double budget = 0.9 * session_.pacing().frame_interval;
  return std::max(1L, long(std::min(budget / step_seconds_, 1e9)));
}

void App::plan_drawing() {
  DrawPlan& plan = plan_;
  plan.views = views();
  plan.overlay = session_.compare() == Compare::overlay && session_.reference();
  plan.note_reference = session_.reference() != nullptr;
  plan.highlighted = session_.problem().kind == Problem::Kind::diverged
                         ? session_.problem().particle
                         : info_.hovered;
  plan.arrows_on = settings_.force_arrows && session_.grabbed() < 0 ? info_.hovered : -1;
  for (int v = 0; v < 2; ++v) {
    const Simulation* sim = v < plan.views ? simulation_of(v) : nullptr;
    RunState& run = plan.runs[std::size_t(v)];
    if (sim) {
      run.capture(*sim, plan.arrows_on >= 0);
      // Not while a particle is held: the world under the mouse must stay where it is.
      if (session_.grabbed() < 0)
        cameras_[std::size_t(v)].keep_in_view(run.position, sim->parameters().spacing);
    } else
      run.sim = nullptr;
  }
  if (plan.overlay)
    plan.ghost.capture(*session_.reference(), false);
  else
    plan.ghost.sim = nullptr;
  label_time_ = session_.time();
}

void App::draw_scenes() {
  window_.clear(colour::background);
  panel_.draw_backgrounds(window_);
  const sf::View whole = window_.getView();
  const sf::Vector2u size = window_.getSize();
  DrawCounts drawn;
  for (int v = 0; v < plan_.views; ++v) {
    const Camera& camera = cameras_[std::size_t(v)];
    const Viewport& area = camera.viewport();
    // A view per viewport clips each run to its half in side-by-side mode.
    sf::View clip(compat::float_rect(area.left, area.top, area.width, area.height));
    clip.setViewport(compat::float_rect(area.left / float(size.x), area.top / float(size.y),
                                        area.width / float(size.x), area.height / float(size.y)));
    window_.setView(clip);
    DrawOptions options = settings_.draw;
    if (v == 0 && plan_.ghost.sim) {
      DrawOptions ghost = options;
      ghost.ghost = true;
      drawn += draw_scene(window_, plan_.ghost, camera, ghost);
    }
    const RunState& run = plan_.runs[std::size_t(v)];
    if (!run.sim) continue;
    options.highlighted = plan_.highlighted;
    drawn += draw_scene(window_, run, camera, options);
    if (plan_.arrows_on >= 0) draw_force_arrows(window_, run, camera, plan_.arrows_on);
  }
  window_.setView(whole);
  info_.drawn = drawn;
}

void App::draw_labels() {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const ImU32 text = IM_COL32(200, 200, 210, 255);
  const Viewport& area = cameras_[0].viewport();
  const double metres = scale_bar_metres(cameras_[0].pixels_per_metre());
  const float pixels = float(metres * cameras_[0].pixels_per_metre());
  const ImVec2 left(area.left + 20, area.top + area.height - 20);
  draw->AddLine(left, ImVec2(left.x + pixels, left.y), text, 2.0f);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", metres);
  draw->AddText(ImVec2(left.x, left.y - 18), text, label);
  std::snprintf(label, sizeof label, "t = %.2f s", label_time_);
  draw->AddText(ImVec2(area.left + 20, area.top + 10), text, label);
  if (plan_.views == 2) {
    draw->AddText(ImVec2(area.left + 20, area.top + 30), text, "your code");
    const Viewport& right = cameras_[1].viewport();
    draw->AddText(ImVec2(right.left + 20, right.top + 30), text, "the reference");
    draw->AddLine(ImVec2(right.left, right.top), ImVec2(right.left, right.top + right.height),
                  IM_COL32(80, 80, 90, 255));
  } else if (plan_.note_reference) {
    draw->AddText(ImVec2(area.left + 20, area.top + 30), text,
                  "yours in colour, the reference in blue");
  }
}

}  // namespace springlab::view
