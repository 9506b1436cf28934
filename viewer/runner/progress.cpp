#include "runner/progress.hpp"

#include "springlab/cli_values.hpp"

#include <cstdio>
#include <ostream>

namespace springlab {
namespace {

// The first steps are timed for this long (or for the whole run, if shorter) before the
// estimate: one step's time alone is noisy, and a slow first step is itself enough.
constexpr double timing_seconds = 0.2;

}  // namespace

std::string step_time_in_words(double seconds) {
  char text[32];
  if (seconds < 1e-3)
    std::snprintf(text, sizeof text, "%.3g \u00b5s", seconds * 1e6);
  else if (seconds < 1.0)
    std::snprintf(text, sizeof text, "%.3g ms", seconds * 1e3);
  else
    std::snprintf(text, sizeof text, "%.2g s", seconds);
  return text;
}

std::string run_estimate(long steps, double seconds_per_step) {
  char count[32];  // a count as a person reads it: 2000, or 1e+09 when it is long
  if (steps < 10000000)
    std::snprintf(count, sizeof count, "%ld", steps);
  else
    std::snprintf(count, sizeof count, "%.3g", double(steps));
  return "this run will take about " + duration_in_words(double(steps) * seconds_per_step) + " (" +
         count + " steps at " + step_time_in_words(seconds_per_step) + " a step)";
}

Progress::Progress(long steps, double duration, std::ostream& out, Settings settings)
    : steps_(steps),
      duration_(duration),
      out_(out),
      settings_(settings),
      start_(std::chrono::steady_clock::now()),
      next_report_(settings.quiet_for) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::after_step(long n, double t) {
  if (!estimated_) warn_if_long(n);
  if (elapsed() >= next_report_ && n < steps_) report(n, t);
}

void Progress::warn_if_long(long n) {
  const double seconds = elapsed();
  if (seconds < timing_seconds && n < steps_) return;
  estimated_ = true;
  const double per_step = seconds / double(n);
  if (per_step * double(steps_) <= settings_.warn_above) return;
  out_ << "springlab-run: " << run_estimate(steps_, per_step)
       << "; press Ctrl-C to stop, or shorten --duration" << std::endl;
}

void Progress::report(long n, double t) {
  const double seconds = elapsed();
  const double left = seconds / double(n) * double(steps_ - n);
  char line[160];
  std::snprintf(line, sizeof line,
                "springlab-run: t = %.6g of %.6g s (%.3g %%), step %ld of %ld; "
                "about %s left",
                t, duration_, 100.0 * double(n) / double(steps_), n, steps_,
                duration_in_words(left).c_str());
  if (settings_.terminal) {
    out_ << '\r' << line << "\033[K" << std::flush;  // \033[K: clear what a longer line left
    line_open_ = true;
  } else {
    out_ << line << std::endl;
  }
  next_report_ = seconds + (settings_.terminal ? settings_.every / 10 : settings_.every);
}

void Progress::finish() {
  if (line_open_) out_ << '\n' << std::flush;
  line_open_ = false;
}

}  // namespace springlab
