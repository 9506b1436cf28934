// The points file: defaults, overrides by exact test name, and errors that name what is wrong.
#include "points.hpp"
#include "submission.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

using namespace springlab::grader;
namespace fs = std::filesystem;

namespace {

const std::string listing =
    "[spring][task1]\tSpring: one\n"
    "[task1]\tSpring: two, with a comma\n"
    "[core]\tNot a task's test\n"
    "[task2][momentum]\tGrid: momentum\n";

fs::path write_points(const std::string& text) {
  const fs::path file = fs::temp_directory_path() / "springlab-points-test.toml";
  std::ofstream(file) << text;
  return file;
}

std::string rejection(std::vector<TestInfo>& tests, const std::string& text) {
  try {
    assign_points(tests, write_points(text));
  } catch (const UsageError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("The harness's list: tests of tasks 1-5 in order, numbered within their task",
          "[points]") {
  const std::vector<TestInfo> tests = parse_test_list(listing);
  REQUIRE(tests.size() == 3);
  CHECK(tests[0].name == "Spring: one");
  CHECK(tests[0].tags == std::vector<std::string>{"spring", "task1"});
  CHECK(tests[1].name == "Spring: two, with a comma");
  CHECK((tests[0].number == 1 && tests[1].number == 2));
  CHECK((tests[2].task == 2 && tests[2].number == 1));
}

TEST_CASE("Points: a default per task, overrides by exact name, and the maximum is the sum",
          "[points]") {
  std::vector<TestInfo> tests = parse_test_list(listing);
  assign_points(tests, write_points("[task1]\ndefault = 2\n\"Spring: two, with a comma\" = 0.5\n"
                                    "[task2]\ndefault = 3\n"));
  CHECK(tests[0].points == 2.0);
  CHECK(tests[1].points == 0.5);
  CHECK(tests[2].points == 3.0);
}

TEST_CASE("Points: a task without a section keeps 1 point a test", "[points]") {
  std::vector<TestInfo> tests = parse_test_list(listing);
  assign_points(tests, write_points("[task2]\ndefault = 4\n"));
  CHECK(tests[0].points == 1.0);
  CHECK(tests[2].points == 4.0);
}

TEST_CASE("Points: mistakes in the file are named with the value and what is allowed", "[points]") {
  std::vector<TestInfo> tests = parse_test_list(listing);
  CHECK_THAT(rejection(tests, "[task1]\n\"Spring: tree\" = 1\n"),
             Catch::Contains("\"Spring: tree\": no test of task 1 has this name") &&
                 Catch::Contains("Spring: one"));
  CHECK_THAT(rejection(tests, "[task1]\ndefault = -1\n"),
             Catch::Contains("task1.default = -1: allowed a number of points from 0 to 1000000"));
  CHECK_THAT(rejection(tests, "[task1]\ndefault = \"two\"\n"),
             Catch::Contains("default = \"two\": allowed a number of points from 0 to 1000000"));
  CHECK_THAT(rejection(tests, "[task1]\ndefault = 1e308\n"),
             Catch::Contains("task1.default = 1e+308: allowed a number of points from 0 to"));
  CHECK_THAT(rejection(tests, "[task9]\ndefault = 1\n"),
             Catch::Contains("[task9]: allowed sections are [task1] ... [task5]"));
  CHECK_THAT(rejection(tests, "[task1\n"), Catch::Contains("springlab-points-test.toml:1"));
}
