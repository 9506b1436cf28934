#include "gui/display.hpp"

#include "springlab/scene_text.hpp"

#include <X11/Xlib.h>

#include <cstdlib>
#include <memory>
#include <ostream>

namespace springlab::view {

bool display_reachable(std::ostream& out) {
  const char* name = std::getenv("DISPLAY");
  if (!name || !*name) {
    out << "springlab-view: DISPLAY is not set.\n";
    return false;
  }
  Display* display = XOpenDisplay(nullptr);
  if (!display) {
    out << "springlab-view: the display " << quoted_for_terminal(name) << " cannot be opened.\n";
    return false;
  }
  // Held open until the program ends: were it the server's only client, closing it would make
  // Xvfb reset, and SFML's own connection a moment later could fail.
  static const std::unique_ptr<Display, int (*)(Display*)> held(display, XCloseDisplay);
  return true;
}

}  // namespace springlab::view
