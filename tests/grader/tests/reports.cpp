// Reports: what a student's output can put in them is made printable, the formats parse back,
// and the gradebook has exactly its header.
#include "reports.hpp"
#include "lab_catch.hpp"

#include <nlohmann/json.hpp>

using namespace springlab::grader;

namespace {

// A submission with one passing and one failing test in task 1 and a task 2 that did not build.
struct Example {
  std::vector<TestInfo> tests = {{"Spring: one", {"task1", "spring"}, 1, 1, 2.0},
                                 {"Spring: two", {"task1"}, 1, 2, 1.0},
                                 {"Grid: one", {"task2"}, 2, 1, 1.5}};
  SubmissionResult result;
  Example(const std::string& name, const std::string& printed) {
    result.submission.name = name;
    TaskResult& one = result.tasks[1];
    one.task = 1;
    one.tests = {
        {&tests[0], true, "", "", 0, 0.1, 0.2},
        {&tests[1], false, "a <bad> & \"quoted\" failure", printed, printed.size(), 0.1, 0}};
    TaskResult& two = result.tasks[2];
    two.task = 2;
    two.problem = "does not compile:\nspring_forces.cpp:3: error: expected ';'";
    two.tests = {{&tests[2], false, "does not compile:", "", 0, 0, 0}};
  }
};

}  // namespace

TEST_CASE("Printable text: no control characters, valid UTF-8, newlines and tabs kept",
          "[reports]") {
  CHECK(printable("a\x1b[2Jb\tc\nd\r") == "a?[2Jb\tc\nd?");
  CHECK(printable("ℓ0 = √2 m") == "ℓ0 = √2 m");
  CHECK(printable("bad \xff\xfe and cut \xe2\x88") == "bad ?? and cut ??");
  // Surrogates, overlong forms and code points above U+10FFFF are not UTF-8 either.
  CHECK(printable("\xed\xa0\x80|\xe0\x80\xaf|\xf0\x80\x80\xaf|\xf4\x90\x80\x80|\xc0\xaf") ==
        "???|???|????|????|??");
  CHECK(printable("\xf0\x9f\x99\x82 \xf4\x8f\xbf\xbf") == "\xf0\x9f\x99\x82 \xf4\x8f\xbf\xbf");
}

TEST_CASE("Points are written as people write them", "[reports]") {
  CHECK(points_text(12) == "12");
  CHECK(points_text(2.5) == "2.5");
  CHECK(points_text(1.0 / 3.0) == "0.33");
}

TEST_CASE(
    "The gradebook: the exact header, points per task and in total, names quoted when "
    "needed",
    "[reports]") {
  const Example plain("alice", ""), odd("o'brien, \"bob\"", ""), formula("=1+2", "");
  CHECK(gradebook({plain.result, odd.result, formula.result}) ==
        "submission,task1,task2,task3,task4,task5,total\n"
        "alice,2,0,,,,2\n"
        "\"o'brien, \"\"bob\"\"\",2,0,,,,2\n"
        "'=1+2,2,0,,,,2\n");
}

TEST_CASE("results.json: Gradescope's fields for every test, and what the code printed made safe",
          "[reports]") {
  const Example e("alice", "printed \x1b[31m red \xff\n");
  const auto json = nlohmann::json::parse(results_json(e.result, 12.4));
  CHECK(json["score"] == 2.0);
  CHECK(json["execution_time"] == 12);
  REQUIRE(json["tests"].size() == 3);
  const auto& failed = json["tests"][1];
  CHECK(failed["name"] == "Task 1: Spring: two");
  CHECK(failed["number"] == "1.2");
  CHECK(failed["status"] == "failed");
  CHECK(failed["score"] == 0.0);
  CHECK(failed["max_score"] == 1.0);
  CHECK(failed["visibility"] == "visible");
  CHECK(failed["tags"] == nlohmann::json::array({"task1"}));
  CHECK_THAT(failed["output"].get<std::string>(),
             lab_catch::Contains("your code printed 20 bytes:\n| printed ?[31m red ?"));
  CHECK(json["tests"][0]["tags"] == nlohmann::json::array({"task1", "spring"}));
  CHECK_THAT(json["tests"][2]["output"].get<std::string>(), lab_catch::Contains("expected ';'"));
}

TEST_CASE("results.json: the top-level output is the summary, and says what files were missing",
          "[reports]") {
  Example e("alice", "");
  auto json = nlohmann::json::parse(results_json(e.result, 1.0));
  CHECK(json["output"] == summary_feedback(e.result));
  e.result.tasks[2].notes = {"structural_springs.cpp is missing: graded as the starter code"};
  json = nlohmann::json::parse(results_json(e.result, 1.0));
  CHECK_THAT(
      json["output"].get<std::string>(),
      lab_catch::StartsWith(summary_feedback(e.result)) &&
          lab_catch::EndsWith("Notes on the files submitted:\n  task 2: structural_springs.cpp "
                              "is missing: graded as the starter code\n"));
}

TEST_CASE("JUnit: one testcase per test, failures escaped", "[reports]") {
  const Example e("alice", "<system-out>");
  const std::string xml = junit_report(e.result, 1);
  CHECK_THAT(xml, lab_catch::Contains("<testsuite name=\"task1\" tests=\"2\" failures=\"1\">"));
  CHECK_THAT(xml,
             lab_catch::Contains("message=\"a &lt;bad&gt; &amp; &quot;quoted&quot; failure\""));
  CHECK(xml.find("<system-out>") == std::string::npos);
}

TEST_CASE("Feedback: one line per test, the failure explained, and a count in points",
          "[reports]") {
  Kit kit;
  kit.task_files = {{1, {"task1_two_masses/spring_damper.cpp"}},
                    {2, {"task2_four_masses/spring_forces.cpp"}}};
  const Example e("alice", "");
  const std::string text = feedback(e.result, kit);
  CHECK_THAT(text,
             lab_catch::Contains("==> Task 1: the code in tasks/task1_two_masses/ (handout "
                                 "section 1)\n  Spring: one ... pass\n  Spring: two ... FAIL\n"
                                 "        a <bad> & \"quoted\" failure\n"));
  CHECK_THAT(text, lab_catch::Contains("1 of 2 tests pass (2 of 3 points); fix the first FAIL"));
  CHECK_THAT(text, lab_catch::Contains("  does not compile:\n  spring_forces.cpp:3: error"));
  CHECK_THAT(text, lab_catch::Contains("==> Summary: 2 of 4.5 points\n  task 1: 1 of 2 tests pass "
                                       "(2 of 3 points); first failure: Spring: two\n"));
  CHECK_THAT(text, lab_catch::Contains("  task 2: does not compile (0 of 1.5 points)"));
}

namespace {

// Task 1 with a public test that passes and a hidden one that fails, worth 3 points.
struct WithHidden {
  std::vector<TestInfo> tests = {{"Spring: one", {"task1", "spring"}, 1, 1, 1.0, false},
                                 {"Spring: secret", {"hidden", "task1"}, 1, 2, 3.0, true}};
  SubmissionResult result;
  WithHidden() {
    result.submission.name = "alice";
    TaskResult& one = result.tasks[1];
    one.task = 1;
    one.tests = {{&tests[0], true, "", "", 0, 0.1, 0.2},
                 {&tests[1], false, "k = 45: the force is 20/45 of Hooke's", "", 0, 0.1, 0}};
  }
};

}  // namespace

TEST_CASE("results.json: a hidden test is shown after the due date, and its result nowhere else",
          "[reports][hidden]") {
  const WithHidden e;
  const auto json = nlohmann::json::parse(results_json(e.result, 1.0));
  REQUIRE(json["tests"].size() == 2);
  CHECK(json["tests"][0]["visibility"] == "visible");
  const auto& hidden = json["tests"][1];
  CHECK(hidden["visibility"] == "after_due_date");
  CHECK(hidden["tags"] == nlohmann::json::array({"task1", "hidden"}));
  CHECK(hidden["max_score"] == 3.0);
  CHECK_THAT(hidden["output"].get<std::string>(), lab_catch::Contains("20/45 of Hooke's"));
  CHECK(json["score"] == 1.0);  // every test counts
  // The run's output, which Gradescope shows at once, counts the public tests only.
  const std::string output = json["output"].get<std::string>();
  CHECK_THAT(output,
             lab_catch::Contains("==> Summary: 1 of 1 points\n  task 1: its 1 test passes"));
  CHECK_THAT(output, lab_catch::Contains("and 1 hidden test (3 points), shown after the due date"));
  CHECK_THAT(output, !lab_catch::Contains("secret") && !lab_catch::Contains("Hooke"));
}

TEST_CASE("Feedback: an instructor sees the hidden tests marked, and the visible part has none",
          "[reports][hidden]") {
  Kit kit;
  kit.task_files = {{1, {"task1_two_masses/spring_damper.cpp"}}};
  const WithHidden e;
  CHECK_THAT(feedback(e.result, kit),
             lab_catch::Contains("  Spring: one ... pass\n  Spring: secret ... FAIL (hidden test: "
                                 "students see it after the due date)\n") &&
                 lab_catch::Contains("1 of 2 tests pass (1 of 4 points)"));
  const SubmissionResult visible = visible_part(e.result);
  CHECK(visible.max_points() == 1.0);
  const std::string text = feedback(visible, kit);
  CHECK_THAT(text, !lab_catch::Contains("secret") && !lab_catch::Contains("hidden"));
  CHECK_THAT(text, lab_catch::Contains("1 of 1 tests pass (1 of 1 points)."));
}

TEST_CASE("Summary: a task not started says what to write first, one that passes says no more",
          "[reports]") {
  const std::vector<TestInfo> tests = {{"Spring: one", {"task1"}, 1, 1, 1.0, false},
                                       {"Spring: two", {"task1"}, 1, 2, 1.0, false}};
  const std::string stub =
      "Task 1 is not implemented yet: write spring_force in "
      "tasks/task1_two_masses/spring_damper.cpp (see handout section 1)";
  SubmissionResult result;
  result.tasks[1].tests = {{&tests[0], false, stub, "", 0, 0.1, 0},
                           {&tests[1], false, stub + "\nmore", "", 0, 0.1, 0}};
  CHECK_THAT(summary_feedback(result),
             lab_catch::Contains("  task 1: not started (write spring_force in "
                                 "tasks/task1_two_masses/spring_damper.cpp, handout section 1)\n"));
  // Its feedback says the stub's message once, not once per test.
  Kit kit;
  kit.task_files = {{1, {"task1_two_masses/spring_damper.cpp"}}};
  const std::string text = feedback(result, kit);
  CHECK_THAT(text,
             lab_catch::Contains("  Spring: one ... not started\n  Spring: two ... not started\n"));
  CHECK(text.find("is not implemented yet") == std::string::npos);
  CHECK_THAT(text, lab_catch::Contains("not started yet: write spring_force in"));
  // Started: one test fails otherwise, so the first failure is named instead.
  result.tasks[1].tests[1].message = "got 0.5 N, expected 1 N";
  CHECK_THAT(
      summary_feedback(result),
      lab_catch::EndsWith("  task 1: 0 of 2 tests pass (0 of 2 points); first failure: Spring: "
                          "one\n"));
  result.tasks[1].tests[0].passed = result.tasks[1].tests[1].passed = true;
  CHECK_THAT(summary_feedback(result),
             lab_catch::EndsWith("  task 1: all 2 tests pass (2 of 2 points)\n"));
}
