// The glue between SFML and Dear ImGui, written for this kit (Debian ships ImGui without an SFML
// backend): SFML events become ImGui input, the window gives ImGui its size and clock, and ImGui
// draws through its own OpenGL 2 backend on the window's context. One per program (ImGui keeps
// one global context).
#pragma once

#include "gui/sfml_compat.hpp"

#include <SFML/Graphics/RenderWindow.hpp>

#include <string>

namespace springlab::view {

class ImGuiGlue {
 public:
  explicit ImGuiGlue(sf::RenderWindow& window);
  ~ImGuiGlue();
  ImGuiGlue(const ImGuiGlue&) = delete;
  ImGuiGlue& operator=(const ImGuiGlue&) = delete;

  /// Passes one event (real or synthetic) to ImGui.
  void handle(const compat::Input& event);
  /// Starts an ImGui frame that lasts `seconds`; widgets may be declared until render().
  void new_frame(float seconds);
  /// Draws the frame's widgets over whatever SFML has drawn.
  void render();

  bool wants_mouse() const;     ///< the mouse is over (or dragging) a widget
  bool wants_keyboard() const;  ///< a text field has the keyboard
  /// The TrueType file the panel's text is drawn with; empty: ImGui's own font (none found).
  const std::string& font_file() const { return font_file_; }

 private:
  sf::RenderWindow& window_;
  std::string font_file_;
};

}  // namespace springlab::view
