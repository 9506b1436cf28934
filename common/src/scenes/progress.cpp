#include "springlab/progress.hpp"

#include "springlab/cli_values.hpp"

#include <cstdio>
#include <ostream>

namespace springlab {
namespace {

// The first steps are timed for this long (or for the whole run, if shorter) before the
// estimate: one step's time alone is noisy, and a slow first step is itself enough.
constexpr double timing_seconds = 0.2;

}  // namespace

std::string time_in_words(double seconds) {
  char text[32];
  if (seconds < 1e-3)
    std::snprintf(text, sizeof text, "%.3g \u00b5s", seconds * 1e6);
  else if (seconds < 1.0)
    std::snprintf(text, sizeof text, "%.3g ms", seconds * 1e3);
  else
    std::snprintf(text, sizeof text, "%.2g s", seconds);
  return text;
}

std::string run_estimate(long count, double seconds_each, std::string_view unit) {
  char number[32];  // a count as a person reads it: 2000, or 1e+09 when it is long
  if (count < 10000000)
    std::snprintf(number, sizeof number, "%ld", count);
  else
    std::snprintf(number, sizeof number, "%.3g", double(count));
  const std::string what(unit);
  return "this run will take about " + duration_in_words(double(count) * seconds_each) + " (" +
         number + " " + what + "s at " + time_in_words(seconds_each) + " a " + what + ")";
}

Progress::Progress(long total, std::ostream& out, Settings settings)
    : total_(total),
      out_(out),
      settings_(std::move(settings)),
      start_(std::chrono::steady_clock::now()),
      next_report_(settings_.quiet_for) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::after(long n, std::string_view where) {
  if (!estimated_) warn_if_long(n);
  if (elapsed() >= next_report_ && n < total_) report(n, where);
}

void Progress::warn_if_long(long n) {
  const double seconds = elapsed();
  // The first unit carries the setup (a window's first frame, the first allocations and caches),
  // measured at 10-100 times a later one's: the estimate comes from the units after it, unless
  // the first alone makes the run so long that waiting for a second would waste the warning.
  if (n == 1) {
    first_unit_ = seconds;
    if (n < total_ && seconds * double(total_) <= 20 * settings_.warn_above) return;
  } else if (seconds - first_unit_ < timing_seconds && n < total_) {
    return;
  }
  estimated_ = true;
  const double each = n > 1 ? (seconds - first_unit_) / double(n - 1) : seconds;
  if (each * double(total_) <= settings_.warn_above) return;
  finish();
  out_ << settings_.program << ": " << run_estimate(total_, each, settings_.unit)
       << "; press Ctrl-C to stop, or " << settings_.shorten << std::endl;
}

void Progress::report(long n, std::string_view where) {
  const double seconds = elapsed();
  const double left = seconds / double(n) * double(total_ - n);
  char line[200];
  std::snprintf(line, sizeof line, "%s: %.*s%s%s %ld of %ld (%.3g %%); about %s left",
                settings_.program.c_str(), int(where.size()), where.data(),
                where.empty() ? "" : ", ", settings_.unit.c_str(), n, total_,
                100.0 * double(n) / double(total_), duration_in_words(left).c_str());
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
