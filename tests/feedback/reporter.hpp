// What the harness's Catch2 reporter ("record") saw of the one test case it ran.
#pragma once

#include <string>

namespace springlab::grading {

struct TestOutcome {
  int cases_run = 0;           ///< test cases that started: exactly 1 when all went well
  long assertions_passed = 0;  ///< over the test case
  long assertions_failed = 0;
  std::string first_failure;  ///< the first failed assertion, explained; "" when none failed

  /// Passed: no assertion failed and at least one ran (a test that checks nothing fails).
  bool passed() const { return assertions_failed == 0 && assertions_passed > 0; }
};

/// The outcome of the run so far (filled by the reporter).
TestOutcome& test_outcome();

}  // namespace springlab::grading
