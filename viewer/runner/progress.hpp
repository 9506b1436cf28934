// What springlab-run says on stderr while a long run goes on: a warning before a run that will
// take more than a few minutes, with its estimate, and its progress (how far, time left) once it
// has lasted a few seconds. Wall time decides only what is printed, never the run's result.
#pragma once

#include <chrono>
#include <iosfwd>
#include <string>

namespace springlab {

/// "180 µs", "2.5 ms", "1.3 s": the time one step takes.
std::string step_time_in_words(double seconds);

/// "this run will take about 2.3 days (1e+09 steps at 180 µs a step)".
std::string run_estimate(long steps, double seconds_per_step);

class Progress {
 public:
  struct Settings {
    double warn_above = 180.0;  ///< s: longer runs are announced before they go on
    double quiet_for = 3.0;     ///< s: no progress lines in a run's first seconds
    double every = 1.0;         ///< s between progress lines (a tenth on a terminal)
    bool terminal = false;      ///< one line updated in place with \r
  };

  /// A run of `steps` steps to `duration` simulated seconds, reported on `out`.
  Progress(long steps, double duration, std::ostream& out, Settings settings);
  /// After step `n` of the run, at simulated time `t`: warns once the first steps' time gives an
  /// estimate, and prints progress when it is due.
  void after_step(long n, double t);
  /// Ends an updated line, if one was printed.
  void finish();
  /// Wall seconds since the run started.
  double elapsed() const;

 private:
  void warn_if_long(long n);
  void report(long n, double t);

  long steps_;
  double duration_;
  std::ostream& out_;
  Settings settings_;
  std::chrono::steady_clock::time_point start_;
  double next_report_;
  bool estimated_ = false;
  bool line_open_ = false;
};

}  // namespace springlab
