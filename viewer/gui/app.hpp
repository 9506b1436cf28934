// The viewer's window: one frame at a time, it reads the events, lets the panel change the
// session, advances the simulation by its fixed steps and draws the scene and the panel. Tests
// and headless runs drive the same object, feeding it synthetic events.
#pragma once

#include "gui/camera.hpp"
#include "gui/imgui_glue.hpp"
#include "gui/panel.hpp"
#include "gui/session.hpp"
#include "gui/sfml_messages.hpp"

#include <SFML/Graphics/Image.hpp>
#include <SFML/Graphics/RenderWindow.hpp>
#include <SFML/System/Clock.hpp>

#include <array>
#include <string>

namespace springlab::view {

struct AppOptions {
  std::string scene = "task5";  ///< task1 … task5 or a scene file
  unsigned width = 1280, height = 800;
  bool frame_rate_limit = true;   ///< 60 frames/s; off for headless runs and benchmarks
  bool fixed_frame_time = false;  ///< ImGui's clock at exactly 1/60 s a frame (repeatable)
};

class App {
 public:
  explicit App(const AppOptions& options);

  bool is_open() const { return window_.isOpen(); }
  /// One frame; with `capture`, keeps a copy of what it drew (captured()).
  void frame(bool capture = false);
  /// One event, real or synthetic, as the window would receive it.
  void handle(const sf::Event& event);

  Session& session() { return session_; }
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
  void draw_scenes();
  void draw_labels();
  void on_press(const sf::Event::MouseButtonEvent& button);
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
  int fitted_to_ = -1;       // the session's fresh start the view was last fitted to
  double label_time_ = 0.0;  // s, the time the label on the scene showed
};

}  // namespace springlab::view
