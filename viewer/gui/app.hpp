// The viewer's window: one frame at a time, it reads the events, lets the panel change the
// session, advances the simulation by its fixed steps and draws the scene and the panel. Tests
// and headless runs drive the same object, feeding it synthetic events.
//
// With a stepping thread (stepper.hpp), a frame takes the session back from the thread, handles
// the events and the panel, copies what it will draw, then hands the thread this frame's steps and
// draws the copy while they are taken: stepping and drawing run on two cores, and the panel, the
// plots, the label and the scene all show the state the frame copied.
#pragma once

#include "gui/camera.hpp"
#include "gui/imgui_glue.hpp"
#include "gui/panel.hpp"
#include "gui/scene_drawing.hpp"
#include "gui/session.hpp"
#include "gui/sfml_messages.hpp"
#include "gui/stepper.hpp"

#include <SFML/Graphics/Image.hpp>
#include <SFML/Graphics/RenderWindow.hpp>
#include <SFML/System/Clock.hpp>
#include <SFML/Window/Event.hpp>

#include <array>
#include <memory>
#include <string>

namespace springlab::view {

/// Where the simulation steps: `automatic` is a thread of its own unless the frame time is fixed
/// (screenshots, --record and the tests then show each frame's state after its own steps).
enum class Stepping { automatic, synchronous, thread };

struct AppOptions {
  std::string scene = "task5";  ///< task1 … task5 or a scene file
  unsigned width = 1280, height = 800;
  bool frame_rate_limit = true;   ///< 60 frames/s; off for headless runs and benchmarks
  bool fixed_frame_time = false;  ///< ImGui's clock at exactly 1/60 s a frame (repeatable)
  Stepping stepping = Stepping::automatic;
};

class App {
 public:
  explicit App(const AppOptions& options);

  bool is_open() const { return window_.isOpen(); }
  /// One frame; with `capture`, keeps a copy of what it drew (captured()). With a stepping
  /// thread, the frame's steps may still be under way when it returns.
  void frame(bool capture = false);
  /// One event, real or synthetic, as the window would receive it.
  void handle(const sf::Event& event);

  /// The session, once the stepping thread (if any) has finished the steps it was given.
  Session& session() {
    finish_stepping();
    return session_;
  }
  /// Waits for the stepping thread to finish the steps it was given, if any.
  void finish_stepping();
  /// The stepping thread's time on steps finished since the last frame or call, s (a frame
  /// reports it as its stepping_seconds); 0 without a thread.
  double take_stepping_seconds() { return stepper_ ? stepper_->take_work_seconds() : 0.0; }
  bool stepping_thread() const { return stepper_ != nullptr; }
  Panel& panel() { return panel_; }
  ViewSettings& settings() { return settings_; }
  sf::RenderWindow& window() { return window_; }
  const FrameInfo& last_frame() const { return info_; }
  /// The camera of view 0 (the chosen code) or view 1 (the reference, side by side).
  const Camera& camera(int view = 0) const { return cameras_[std::size_t(view)]; }
  const sf::Image& captured() const { return captured_; }
  /// The time the scene's label showed in the last frame, s (the panel's: panel().shown_time()).
  double label_time() const { return label_time_; }
  void fit();

 private:
  int views() const;
  const Simulation* simulation_of(int view) const;
  int view_at(sf::Vector2f point) const;
  int hovered() const;
  void layout();
  long most_steps() const;
  void plan_drawing();
  void draw_scenes();
  void draw_labels();
  void on_press(sf::Mouse::Button button);
  void on_key(sf::Keyboard::Key key);

  AppOptions options_;
  SfmlMessageFilter sfml_messages_;  // before window_: making it prints the line it drops
  sf::RenderWindow window_;
  ImGuiGlue glue_;  // after window_: ImGui's GL objects go before the window's context
  Session session_;
  Panel panel_;
  ViewSettings settings_;
  std::array<Camera, 2> cameras_;
  FrameInfo info_;
  sf::Clock clock_;
  sf::Image captured_;
  sf::Vector2f mouse_{-1.0f, -1.0f};
  bool panning_ = false;
  bool shift_ = false;
  int fitted_to_ = -1;         // the session's fresh start the view was last fitted to
  double step_seconds_ = 0.0;  // s, the stepping thread's time a step, averaged over frames
  long launched_steps_ = 0;    // the steps handed to the stepping thread last
  double label_time_ = 0.0;    // s, the time the label on the scene showed
  // What the frame draws, copied before the stepping thread goes on (plan_drawing).
  struct DrawPlan {
    int views = 1;
    bool overlay = false;         // the reference drawn under the chosen code's run in view 0
    bool note_reference = false;  // the label says which colour is which
    int highlighted = -1;
    int arrows_on = -1;            // the particle whose forces are drawn, or -1
    std::array<RunState, 2> runs;  // view 0 (the chosen code) and view 1 (the reference)
    RunState ghost;                // the reference in overlay mode
  } plan_;
  std::unique_ptr<Stepper> stepper_;  // last: stops before the session it steps goes
};

}  // namespace springlab::view
