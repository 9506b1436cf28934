// Numbers the core's files share: a constant and the way messages print a value. Private to the
// core library.
#pragma once

#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

namespace springlab::internal {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

// x to `digits` significant digits, as the kit's messages print measured values ("0.0123").
inline std::string significant(double x, int digits = 3) {
  std::ostringstream out;
  out << std::setprecision(digits) << x;
  return out.str();
}

}  // namespace springlab::internal
