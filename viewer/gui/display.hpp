// Whether a window can open at all. SFML aborts the program when it cannot reach the X display,
// so springlab-view asks X first and explains. (Kept apart: Xlib's macros clash with C++ names.)
#pragma once

#include <iosfwd>

namespace springlab::view {

/// True when DISPLAY names a display that accepts a connection; otherwise says why on `out`.
bool display_reachable(std::ostream& out);

}  // namespace springlab::view
