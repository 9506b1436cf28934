// The glue between SFML and Dear ImGui, written for this kit (Debian ships ImGui without an SFML
// backend): SFML events become ImGui input, the window gives ImGui its size and clock, and ImGui
// draws through its own OpenGL 2 backend on the window's context. One per program (ImGui keeps
// one global context).
#pragma once

#include <SFML/Graphics/RenderWindow.hpp>
#include <SFML/Window/Event.hpp>

#include <array>

namespace springlab::view {

class ImGuiGlue {
 public:
  explicit ImGuiGlue(sf::RenderWindow& window);
  ~ImGuiGlue();
  ImGuiGlue(const ImGuiGlue&) = delete;
  ImGuiGlue& operator=(const ImGuiGlue&) = delete;

  /// Passes one event (real or synthetic) to ImGui.
  void handle(const sf::Event& event);
  /// Starts an ImGui frame that lasts `seconds`; widgets may be declared until render().
  void new_frame(float seconds);
  /// Draws the frame's widgets over whatever SFML has drawn.
  void render();

  bool wants_mouse() const;     ///< the mouse is over (or dragging) a widget
  bool wants_keyboard() const;  ///< a text field has the keyboard

 private:
  static constexpr std::size_t buttons = 3;  // left, right, middle
  sf::RenderWindow& window_;
  std::array<bool, buttons> down_{};
  // A press and its release can arrive within one frame: the press is latched so ImGui still
  // sees the button down for one frame and registers the click.
  std::array<bool, buttons> pressed_{};
};

}  // namespace springlab::view
