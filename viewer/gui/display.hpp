// Whether a window can open at all. SFML aborts the program when it cannot reach the X display,
// so on X11 systems (Linux, the BSDs) springlab-view asks X first and explains. (Kept apart:
// Xlib's macros clash with C++ names.) macOS and Windows always have their window system: there
// the window just opens. CMake defines SPRINGLAB_VIEW_X11 where it builds display.cpp.
#pragma once

#include <iosfwd>

namespace springlab::view {

#ifdef SPRINGLAB_VIEW_X11
/// True when DISPLAY names a display that accepts a connection; otherwise says why on `out`.
bool display_reachable(std::ostream& out);
#else
inline bool display_reachable(std::ostream&) {
  return true;
}
#endif

}  // namespace springlab::view
