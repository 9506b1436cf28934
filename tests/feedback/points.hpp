// The points of every test, from the instructor's file (tests/points.toml, documented there and in
// the README): a default per task, one for its hidden tests, and overrides per test, by the
// test's exact name. Hidden tests (tagged [hidden], tests/hidden/) are graded like the others but
// shown to students only after the due date; a student's own check leaves them out.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace springlab::grader {

/// One of the kit's tests, as the harness lists it.
struct TestInfo {
  std::string name;               ///< Catch2's test name
  std::vector<std::string> tags;  ///< without brackets: "task1", "spring", ...
  int task = 0;                   ///< from the [taskN] tag
  int number = 0;                 ///< its place within its task: 1, 2, ...
  double points = 1.0;            ///< from the points file
  bool hidden = false;            ///< tagged [hidden]: its result is shown after the due date
};

/// Parses the harness's --list output ("[tag][tag]<TAB>name" lines), keeping the tests of tasks
/// 1-5 in order, each task's hidden tests after its public ones (so a public test has the same
/// number with or without them).
std::vector<TestInfo> parse_test_list(const std::string& listing);

/// The tests of `task` to run, in order: all of them, or (a student's check) the public ones.
std::vector<const TestInfo*> tests_of_task(const std::vector<TestInfo>& tests, int task,
                                           bool with_hidden);

/// Reads the points file and sets every test's points: per [taskN], `default` for each test,
/// `hidden` for each hidden test (default: `default`), then any test by its exact name. Throws
/// UsageError naming the file, the key, the value and what is allowed.
void assign_points(std::vector<TestInfo>& tests, const std::filesystem::path& file);

}  // namespace springlab::grader
