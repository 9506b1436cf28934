// The Dear ImGui panel beside the scene: what runs (scene, code, comparison), how it is stepped
// (integrator, h with its critical step, pacing), every scene parameter, what is shown, the
// particle under the mouse, live plots, and the banner when something went wrong.
#pragma once

#include "gui/camera.hpp"
#include "gui/parameter_widgets.hpp"
#include "gui/scene_drawing.hpp"
#include "gui/session.hpp"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace springlab::view {

/// What the user chose to see and do, beyond the simulation itself.
struct ViewSettings {
  DrawOptions draw;
  bool force_arrows = true;
  int selected = -1;             ///< the particle the panel describes (last clicked)
  Vec2 push_velocity{0.0, 2.0};  ///< m/s, added by a push
};

/// Where a frame's wall time went, s. Software OpenGL rasterises when the frame is shown, so the
/// rasterising of the scene and the panel counts in `display`, not where it was asked for.
struct FramePhases {
  double panel = 0.0;     ///< events and building the ImGui panel and plots
  double stepping = 0.0;  ///< advancing the simulation, or waiting for the stepping thread to
  double thread = 0.0;    ///< the stepping thread's own time for the steps it finished
  double scene = 0.0;     ///< the springs and particles: geometry, pixels, texture upload
  double imgui = 0.0;     ///< handing ImGui's triangles to OpenGL
  double display = 0.0;   ///< rasterising (software OpenGL) and swapping the buffers
};

/// How the last frame went, for the panel's read-outs.
struct FrameInfo {
  double frame_seconds = 0.0;     ///< wall time of the last frame
  double stepping_seconds = 0.0;  ///< of which stepping the simulation
  FramePhases phases;             ///< the phases of the frame before, timed
  long steps = 0;                 ///< steps taken in the last frame
  long dropped_steps = 0;         ///< steps due in the last frame that it could not take
  int hovered = -1;               ///< particle under the mouse
  DrawCounts drawn;               ///< what the scene's views drew in the last frame
};

struct PanelRequests {
  bool fit = false;  ///< fit the view to the scene
};

class Panel {
 public:
  static constexpr float width = 400.0f;        // pixels, at the window's right edge
  static constexpr float plot_height = 170.0f;  // pixels, the plots under the scene

  PanelRequests draw(Session& session, ViewSettings& settings, const FrameInfo& frame,
                     const Viewport& scene_area);

  /// The rectangle of a widget drawn in the last frame: a parameter key ("structural.k",
  /// "step", …) or "run", "step once", "reset", "scene file", "load", "banner", "banner reset".
  std::optional<WidgetRect> rect(const std::string& name) const;
  /// Fills the panel's and the plots' windows with their background colour. Software OpenGL
  /// shades ImGui's triangles (textured, blended) at about 12 ns a pixel, and these two windows
  /// were 470,000 of the 740,000 pixels ImGui drew a frame: so ImGui leaves them out and this
  /// draws them as two plain rectangles. Call before rendering ImGui.
  void draw_backgrounds(sf::RenderTarget& target) const;
  /// The time the panel showed in the last frame, s, and that of the plots' last point.
  double shown_time() const { return shown_time_; }
  double shown_plot_time() const { return shown_plot_time_; }
  /// Whether the banner (a problem) was shown in the last frame.
  bool banner_shown() const { return banner_shown_; }

 private:
  void scene_section(Session& session);
  void run_section(Session& session, PanelRequests& requests);
  void stepping_section(Session& session, const FrameInfo& frame);
  void display_section(Session& session, ViewSettings& settings);
  void particle_section(Session& session, ViewSettings& settings, const FrameInfo& frame);
  void plots(const Session& session, const Viewport& scene_area);
  void banner(Session& session, const Viewport& scene_area);
  void difference_note(const Session& session, const Viewport& scene_area);
  void remember(const std::string& name);
  void remember_background();

  double shown_time_ = 0.0, shown_plot_time_ = 0.0;  // s
  ParameterWidgets parameters_;
  std::map<std::string, WidgetRect> rects_;
  std::vector<WidgetRect> backgrounds_;  // the windows drawn without ImGui's background
  std::vector<WidgetRect> plot_frames_;  // drawn in plot_background by draw_backgrounds
  // The spring families the simulations of build number families_of_build_ have.
  std::array<bool, std::size(spring_families)> present_families_{};
  int families_of_build_ = -1;
  std::array<char, 512> file_{};
  bool banner_shown_ = false;
};

}  // namespace springlab::view
