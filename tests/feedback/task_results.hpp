// A task's results as a student reads them, whoever ran the tests: the grader (sandboxed, Linux)
// or a student's check on their own machine (springlab-check, tests/check/). Plain data.
#pragma once

#include "points.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace springlab::grader {

struct TestResult {
  const TestInfo* test = nullptr;
  bool passed = false;
  std::string message;  ///< why it failed, for the student
  std::string printed;  ///< what the code printed in the deciding run (the kept part)
  std::size_t printed_bytes = 0;
  double seconds = 0.0;            ///< the plain run's wall time
  double sanitized_seconds = 0.0;  ///< the sanitized run's, when it ran
};

struct TaskResult {
  int task = 0;
  std::vector<std::string> notes;  ///< files left out or replaced by the starter code
  std::string problem;  ///< why no test could run (does not compile, rejected); "" otherwise
  /// Why the task was not graded because of the grader itself (its disk full, a submission it
  /// could not read, a process it could not start): never the student's grade. "" otherwise.
  std::string fault;
  std::string warnings;             ///< what the compiler said of code that compiled
  std::vector<std::string> review;  ///< calls no task needs, for the instructor (checks.hpp)
  std::vector<TestResult> tests;
  double points() const;
  double max_points() const;
  int passed() const;
};

}  // namespace springlab::grader
