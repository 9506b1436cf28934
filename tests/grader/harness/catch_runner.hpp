// Catch2's session, as the harness uses it. Catch2 2 declares its Session only where its whole
// implementation is compiled (catch_runner.cpp, about 15 s), so the rest of the harness reaches
// it through these two functions.
#pragma once

#include <string>

namespace springlab::grading {

/// Every test tagged [task<task>]: "[tag][tag]<TAB>name" lines, in the order they were declared.
std::string list_tests(int task);

/// Runs the one test named exactly `name` with the reporter "record" (reporter.hpp).
void run_test_named(const std::string& name);

}  // namespace springlab::grading
