// The ways springlab-view runs a window: interactively until closed, for a number of frames
// (saving a screenshot or every frame), or as a frame-time benchmark.
#pragma once

#include "gui/app.hpp"

#include <iosfwd>
#include <string>

namespace springlab::view {

struct RunOptions {
  long frames = 0;         ///< 0: until the window is closed
  std::string screenshot;  ///< PNG written after the last frame
  std::string record;      ///< a directory for every frame as frame_00000.png, …
  bool benchmark = false;  ///< report frame-time percentiles and steps per second
};

/// Runs `app` as asked and prints what happened; returns the exit code (0, or 3 when the run
/// ended diverged, 4 when the student's code is not written yet). Throws InvalidParameter when
/// a file cannot be written.
int run(App& app, const RunOptions& options, std::ostream& out);

/// "scene task4: 3x3 grid, 9 particles, 20 springs" and what ran on it.
void print_summary(const Session& session, std::ostream& out);

}  // namespace springlab::view
