// The points file: defaults, overrides by exact test name, and errors that name what is wrong.
#include "points.hpp"
#include "lab_catch.hpp"
#include "submission.hpp"

#include <unistd.h>

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
  const fs::path file =
      fs::temp_directory_path() / ("springlab-points-test-" + std::to_string(getpid()) + ".toml");
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
             lab_catch::Contains("\"Spring: tree\": no test of task 1 has this name") &&
                 lab_catch::Contains("Spring: one"));
  CHECK_THAT(
      rejection(tests, "[task1]\ndefault = -1\n"),
      lab_catch::Contains("task1.default = -1: allowed a number of points from 0 to 1000000"));
  CHECK_THAT(
      rejection(tests, "[task1]\ndefault = \"two\"\n"),
      lab_catch::Contains("default = \"two\": allowed a number of points from 0 to 1000000"));
  CHECK_THAT(rejection(tests, "[task1]\ndefault = 1e308\n"),
             lab_catch::Contains("task1.default = 1e+308: allowed a number of points from 0 to"));
  CHECK_THAT(rejection(tests, "[task9]\ndefault = 1\n"),
             lab_catch::Contains("[task9]: allowed sections are [task1] ... [task5]"));
  CHECK_THAT(rejection(tests, "[task1\n"), lab_catch::Contains(".toml:1"));
}

namespace {

// Task 1 with a hidden test listed between its public ones, as a harness could list them.
const std::string listing_with_hidden =
    "[spring][task1]\tSpring: one\n"
    "[hidden][task1]\tSpring: hidden\n"
    "[task1]\tSpring: two\n"
    "[task2][hidden]\tGrid: hidden\n";

}  // namespace

TEST_CASE("Hidden tests: known by their tag, numbered after their task's public tests",
          "[points][hidden]") {
  const std::vector<TestInfo> tests = parse_test_list(listing_with_hidden);
  REQUIRE(tests.size() == 4);
  CHECK((tests[0].name == "Spring: one" && !tests[0].hidden && tests[0].number == 1));
  CHECK((tests[1].name == "Spring: two" && !tests[1].hidden && tests[1].number == 2));
  CHECK((tests[2].name == "Spring: hidden" && tests[2].hidden && tests[2].number == 3));
  CHECK((tests[3].task == 2 && tests[3].hidden && tests[3].number == 1));
}

TEST_CASE("Hidden tests: run in an instructor's grading, left out of a student's check",
          "[points][hidden]") {
  const std::vector<TestInfo> tests = parse_test_list(listing_with_hidden);
  const auto names = [](const std::vector<const TestInfo*>& chosen) {
    std::vector<std::string> result;
    for (const TestInfo* test : chosen)
      result.push_back(test->name);
    return result;
  };
  CHECK(names(tests_of_task(tests, 1, true)) ==
        std::vector<std::string>{"Spring: one", "Spring: two", "Spring: hidden"});
  CHECK(names(tests_of_task(tests, 1, false)) ==
        std::vector<std::string>{"Spring: one", "Spring: two"});
  CHECK(tests_of_task(tests, 2, false).empty());
}

TEST_CASE("Points of hidden tests: the task's default, its `hidden` key, or their own by name",
          "[points][hidden]") {
  std::vector<TestInfo> tests = parse_test_list(listing_with_hidden);
  assign_points(tests, write_points("[task1]\ndefault = 2\n[task2]\ndefault = 3\n"));
  CHECK(tests[2].points == 2.0);  // no `hidden` key: like the others
  CHECK(tests[3].points == 3.0);
  assign_points(tests, write_points("[task1]\ndefault = 2\nhidden = 5\n"
                                    "[task2]\nhidden = 0.5\n\"Grid: hidden\" = 4\n"));
  CHECK(tests[0].points == 2.0);
  CHECK(tests[1].points == 2.0);
  CHECK(tests[2].points == 5.0);
  CHECK(tests[3].points == 4.0);  // its name wins over the key
  CHECK_THAT(
      rejection(tests, "[task1]\nhidden = -1\n"),
      lab_catch::Contains("task1.hidden = -1: allowed a number of points from 0 to 1000000"));
}
