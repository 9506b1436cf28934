// The points of every test, from the instructor's file (tests/points.toml, documented there and in
// the README): a default per task and overrides per test, by the test's exact name.
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
};

/// Parses the harness's --list output ("[tag][tag]<TAB>name" lines), keeping the tests of tasks
/// 1-5 in order.
std::vector<TestInfo> parse_test_list(const std::string& listing);

/// Reads the points file and sets every test's points. Throws UsageError naming the file, the
/// key, the value and what is allowed.
void assign_points(std::vector<TestInfo>& tests, const std::filesystem::path& file);

}  // namespace springlab::grader
