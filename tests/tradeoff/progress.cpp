// Progress on stderr and the short number formats of the tables.
#include "measure.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace springlab::tradeoff {

void Progress::begin(const std::string& what) {
  if (start_ < 0.0) start_ = now();
  what_ = what;
}

void Progress::done(double work) {
  done_ += work;
  const double t = now(), elapsed = t - start_;
  // A line a second at most: enough to see it move, few enough to read.
  if (t - last_print_ < 1.0 && done_ < total_) return;
  last_print_ = t;
  const double fraction = std::min(1.0, done_ / total_);
  std::cerr << "tradeoff: " << std::lround(100.0 * fraction) << " % after " << seconds(elapsed);
  if (fraction > 0.02 && fraction < 1.0)
    std::cerr << ", about " << seconds(elapsed * (1.0 - fraction) / fraction) << " left";
  std::cerr << " (" << what_ << ")\n";
}

std::string number(double x, int digits) {
  if (std::isnan(x)) return "-";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out.precision(digits);
  out << x;
  return out.str();
}

std::string seconds(double s) {
  char text[32];
  if (s < 1e-3)
    std::snprintf(text, sizeof text, "%.3g us", s * 1e6);
  else if (s < 1.0)
    std::snprintf(text, sizeof text, "%.3g ms", s * 1e3);
  else if (s < 120.0)
    std::snprintf(text, sizeof text, "%.3g s", s);
  else
    std::snprintf(text, sizeof text, "%dm%02ds", int(s) / 60, int(s) % 60);
  return text;
}

}  // namespace springlab::tradeoff
