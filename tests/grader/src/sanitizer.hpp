// AddressSanitizer's and UndefinedBehaviorSanitizer's reports (and Eigen's assertions, which the
// sanitized build keeps) said as a student can act on them: what kind of error, in which of the
// student's functions, at which line.
#pragma once

#include <string>

namespace springlab::grader {

/// The first sanitizer report or failed assertion in `output`, as a sentence; "" when none.
std::string explain_sanitizer_report(const std::string& output);

}  // namespace springlab::grader
