// Catch2's session, as the grader's harness and a student's check use it. Catch2 2 declares its
// Session only where its whole implementation is compiled (catch_runner.cpp, about 15 s), so the
// rest of a program reaches it through these functions.
#pragma once

#include <string>

namespace springlab::grading {

/// Every test tagged [task<task>]: "[tag][tag]<TAB>name" lines, in the order they were declared.
std::string list_tests(int task);

/// Runs the one test named exactly `name` with the reporter "record" (reporter.hpp).
void run_test_named(const std::string& name);

/// Catch2's own main: its command line as given (CTest's discovery of a program's tests).
int run_catch_main(int argc, char** argv);

}  // namespace springlab::grading
