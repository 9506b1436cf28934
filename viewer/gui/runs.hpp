// The ways springlab-view runs a window: interactively until closed, for a number of frames
// (saving a screenshot or every frame), or as a frame-time benchmark.
#pragma once

#include "gui/app.hpp"

#include <iosfwd>
#include <stdexcept>
#include <string>

namespace springlab::view {

/// An image or standard output that could not be written (a full disk, a closed pipe): the
/// output is lost, exit 6. The message names the option, the value as written and the file.
class OutputLost : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  long frames = 0;         ///< 0: until the window is closed
  std::string screenshot;  ///< PNG written after the last frame
  std::string record;      ///< a directory for every frame as frame_00000.png, …
  bool benchmark = false;  ///< report frame-time percentiles and steps per second
  bool terminal = false;   ///< the progress goes to a terminal: one line updated in place
};

/// Runs `app` as asked and prints what happened: the summary on `out` (standard output), what
/// went wrong, the estimate of a long headless run and its progress on `err`. Returns the exit
/// code (0, or 3 when the run ended diverged, 4 when the student's code is not written yet, 6
/// when `out` could not be written). Throws OutputLost when an image cannot be written in full.
int run(App& app, const RunOptions& options, std::ostream& out, std::ostream& err);

/// "scene task4: 3x3 grid, 9 particles, 20 springs" and what ran on it, the user's text escaped.
void print_summary(const Session& session, std::ostream& out);

/// What stopped the session ("springlab-view: The simulation diverged at ..."), if anything.
void print_problem(const Session& session, std::ostream& err);

}  // namespace springlab::view
