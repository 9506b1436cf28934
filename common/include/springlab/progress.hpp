// What a front end says on stderr while a long run goes on: a warning before a run that will take
// more than a few minutes, with its estimate, and its progress (how far, time left) once it has
// lasted a few seconds. springlab-run counts steps, springlab-view's headless runs frames. Wall
// time decides only what is printed, never a run's result.
#pragma once

#include <chrono>
#include <iosfwd>
#include <string>
#include <string_view>

namespace springlab {

/// "180 µs", "2.5 ms", "1.3 s": the time one step or frame takes.
std::string time_in_words(double seconds);

/// "this run will take about 2.3 days (1e+09 steps at 180 µs a step)"; `unit` is "step" or
/// "frame".
std::string run_estimate(long count, double seconds_each, std::string_view unit = "step");

class Progress {
 public:
  struct Settings {
    std::string program = "springlab-run";       ///< who speaks
    std::string unit = "step";                   ///< what is counted
    std::string shorten = "shorten --duration";  ///< how to ask for less
    double warn_above = 180.0;                   ///< s: longer runs are announced before they go on
    double quiet_for = 3.0;                      ///< s: no progress lines in a run's first seconds
    double every = 1.0;     ///< s between progress lines (a tenth on a terminal)
    bool terminal = false;  ///< one line updated in place with \r
  };

  /// A run of `total` steps or frames, reported on `out`.
  Progress(long total, std::ostream& out, Settings settings);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { finish(); }

  /// After step or frame `n` (1 for the first): warns once the first ones' time gives an
  /// estimate, and prints progress when it is due, starting with `where` when it is not empty
  /// (e.g. "t = 1.2 of 10 s").
  void after(long n, std::string_view where = "");
  /// Ends an updated line, if one was printed: what follows starts on a line of its own.
  void finish();
  /// Wall seconds since the run started.
  double elapsed() const;

 private:
  void warn_if_long(long n);
  void report(long n, std::string_view where);

  long total_;
  std::ostream& out_;
  Settings settings_;
  std::chrono::steady_clock::time_point start_;
  double next_report_;
  bool estimated_ = false;
  double first_unit_ = 0.0;  // s, the first unit's time (it carries the setup)
  bool line_open_ = false;
};

}  // namespace springlab
