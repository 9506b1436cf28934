// Verdicts: only a record carrying the run's secret, followed by a clean exit, counts; every
// other ending is a failure with its reason.
#include "verdict.hpp"
#include "lab_catch.hpp"
#include "sanitizer.hpp"
#include "words.hpp"

#include <csignal>

using namespace springlab::grader;

namespace {

const std::string secret = "0123456789abcdef0123456789abcdef";

std::string record(const std::string& kind, const std::string& payload,
                   const std::string& key = secret) {
  return key + " " + kind + " " + std::to_string(payload.size()) + "\n" + payload;
}

Outcome ended(int code, const std::string& records, const std::string& output = "") {
  Outcome o;
  o.exited = true;
  o.exit_code = code;
  o.records = records;
  o.output = output;
  o.output_bytes = output.size();
  return o;
}

RunVerdict verdict_of(const Outcome& o) {
  return judge(o, secret, Limits{}, {"10 times the reference's time, at least 2 s"});
}

}  // namespace

TEST_CASE("Secrets: 32 hex digits, a new one each time", "[verdict]") {
  const std::string a = new_secret(), b = new_secret();
  CHECK(a.size() == 32);
  CHECK(a.find_first_not_of("0123456789abcdef") == std::string::npos);
  CHECK(a != b);
}

// The harness's records after a worker that finished cleanly, or ended as `worker` says.
std::string records(const std::string& verdict,
                    const std::string& worker = "loaded 1\ncomplete 1\nexit 0\n",
                    const std::string& key = secret) {
  return record("worker", worker, key) + record("verdict", verdict, key);
}

TEST_CASE("A verdict with the secret, from a harness that ended cleanly, counts", "[verdict]") {
  CHECK(verdict_of(ended(0, records("pass 12 0\n"))).passed);
  const RunVerdict failed = verdict_of(ended(0, records("fail 3 1\nwhy")));
  CHECK_FALSE(failed.passed);
  CHECK(failed.message == "why");
}

TEST_CASE("Records without the secret, or from a harness that did not end cleanly, never pass",
          "[verdict]") {
  const RunVerdict forged = verdict_of(
      ended(0, records("pass 12 0\n", "loaded 1\ncomplete 1\nexit 0\n", std::string(32, '0')),
            "8 of 8 tests pass.\nAll tests passed\n"));
  CHECK_FALSE(forged.passed);
  CHECK_THAT(forged.message, lab_catch::Contains("ended without a verdict"));
  CHECK_FALSE(verdict_of(ended(1, records("pass 12 0\n"))).passed);
  // Bytes before the records neither hide them nor make them count more.
  CHECK(verdict_of(ended(0, "junk " + secret + " nonsense\n" + records("pass 1 0\n"))).passed);
}

TEST_CASE("How the worker ended explains a failure better than the test's first failure",
          "[verdict]") {
  const auto why = [](const std::string& worker, const std::string& output = "") {
    return verdict_of(
               ended(0, records("fail 0 1\nthrew: the code under test stopped", worker), output))
        .message;
  };
  CHECK_THAT(why("loaded 1\ncomplete 0\nsignal 11\nstopped the code under test stopped\n"),
             lab_catch::StartsWith("crashed: segmentation fault"));
  CHECK_THAT(why("loaded 0\ncomplete 0\nexit 0\nstopped the code under test stopped\n"),
             lab_catch::Contains("ended while your code was being loaded"));
  CHECK_THAT(why("loaded 1\ncomplete 0\nexit 0\nstopped the code under test stopped\n"),
             lab_catch::Contains("exited before the test finished (exit status 0)"));
  CHECK_THAT(why("loaded 1\ncomplete 0\nexit 0\nstopped forbidden 59\n"),
             lab_catch::Contains("(" + system_call_name(59) + ")"));
  CHECK_THAT(why("loaded 0\ncomplete 0\nexit 0\nstopped refused your code loaded x\n"),
             lab_catch::Contains("not run: your code loaded x"));
  CHECK_THAT(why("loaded 1\ncomplete 0\nsignal 9\nmemory 1024\n"),
             lab_catch::Contains("used more than 1024 MB of memory"));
  CHECK_THAT(why("loaded 1\ncomplete 1\nexit 0\nstopped call 3 was shear_springs\n"),
             lab_catch::Contains("could not be checked: call 3 was shear_springs"));
  CHECK(why("loaded 1\ncomplete 1\nexit 0\n") == "threw: the code under test stopped");
  CHECK_THAT(why("loaded 1\ncomplete 0\nexit 1\n",
                 "==1==ERROR: AddressSanitizer: SEGV on unknown address 0x0\n"),
             lab_catch::StartsWith("memory error: an access to an address"));
}

TEST_CASE("Limits the grader enforces on the test's processes say what was hit", "[verdict]") {
  Outcome crashed;
  crashed.signal = SIGSEGV;
  CHECK_THAT(verdict_of(crashed).message, lab_catch::Contains("ended without a verdict"));
  Outcome slow;
  slow.stopped = Stop::wall_time;
  slow.wall_seconds = 2.04;
  CHECK_THAT(
      verdict_of(slow).message,
      lab_catch::Contains("timed out: stopped after 2 s (the limit is 10 times the reference's "
                          "time, at least 2 s"));
  Outcome flood;
  flood.stopped = Stop::output;
  CHECK_THAT(verdict_of(flood).message, lab_catch::Contains("printed more than 8 MB"));
}

TEST_CASE("Sanitizer reports become sentences naming the student's function and line",
          "[verdict][sanitizer]") {
  const std::string heap =
      "==1==ERROR: AddressSanitizer: heap-buffer-overflow on address 0x6 at pc 0x5 bp 0x7\n"
      "WRITE of size 8 at 0x6 thread T0\n"
      "    #0 0x7f in springlab::submission::accumulate_spring_forces(std::vector<springlab::"
      "Spring, std::allocator<springlab::Spring> > const&, Eigen::Matrix<double, 2, -1, 0, 2, -1> "
      "const&) /w/submissions/1-a/tasks/task2_four_masses/spring_forces.cpp:13\n"
      "    #1 0x5a in main /k/tests/grader/harness/main.cpp:9\n"
      "0x6 is located 0 bytes to the right of 64-byte region [0x6,0x6)\n";
  CHECK(explain_sanitizer_report(heap) ==
        "memory error (heap-buffer-overflow): your code writes 8 bytes just past the end of an "
        "array (a loop one step too far, or an index out of range?) in accumulate_spring_forces "
        "(tasks/task2_four_masses/spring_forces.cpp, line 13)");
  // The same in the words of GCC 14's AddressSanitizer, and an access before the start.
  std::string after = heap;
  after.replace(after.find("to the right of"), 15, "after");
  CHECK(explain_sanitizer_report(after) == explain_sanitizer_report(heap));
  for (const char* words : {"to the left of", "before"}) {
    std::string before = heap;
    before.replace(before.find("to the right of"), 15, words);
    CHECK_THAT(explain_sanitizer_report(before),
               lab_catch::Contains("writes 8 bytes before the start of an array"));
  }
  const std::string scope =
      "==1==ERROR: AddressSanitizer: stack-use-after-scope on address 0x7\n"
      "READ of size 8 at 0x7 thread T0\n"
      "    #0 0x7f in springlab::submission::f() /w/tasks/task2_four_masses/a.cpp:7:3\n";
  CHECK_THAT(
      explain_sanitizer_report(scope),
      lab_catch::StartsWith("memory error (stack-use-after-scope): your code reads 8 bytes of "
                            "a value whose lifetime had ended in f "
                            "(tasks/task2_four_masses/a.cpp, line 7)") &&
          lab_catch::Contains("Vec2 x = a + b;"));
  CHECK(explain_sanitizer_report("/w/tasks/task1_two_masses/a.cpp:5:12: runtime error: signed "
                                 "integer overflow: 2147483647 + 1\n") ==
        "undefined behaviour (tasks/task1_two_masses/a.cpp, line 5): signed integer overflow: "
        "2147483647 + 1");
  CHECK(explain_sanitizer_report("nothing wrong here\n").empty());
}

TEST_CASE("A failed Eigen check is said in a student's words, without Eigen's text or paths",
          "[verdict][sanitizer]") {
  // The line assert() prints, with the sanitizer's stack after it (issue 38).
  const std::string stack =
      "    #3 0x7f in springlab::submission::hold_pinned(std::vector<bool> const&, "
      "Eigen::Matrix<double, 2, -1, 0, 2, -1>&) /w/1-a/tasks/task5_fabric/pins.cpp:8:5\n";
  const auto failed = [&stack](const std::string& file, const std::string& function,
                               const std::string& condition) {
    return "worker: /usr/include/eigen3/Eigen/src/Core/" + file + ": " + function +
           ": Assertion `" + condition + "' failed.\n" + stack;
  };
  const std::string block_condition =
      "(i>=0) && ( ((BlockRows==1) && (BlockCols==XprType::ColsAtCompileTime) && "
      "i<xpr.rows()) ||((BlockRows==XprType::RowsAtCompileTime) && (BlockCols==1) && "
      "i<xpr.cols()))";
  const std::string column = explain_sanitizer_report(failed(
      "Block.h:120",
      "Eigen::Block<XprType, BlockRows, BlockCols, InnerPanel>::Block(XprType&, Eigen::Index) "
      "[with XprType = Eigen::Matrix<double, 2, -1>; int BlockRows = 2; int BlockCols = 1; bool "
      "InnerPanel = true; Eigen::Index = long int]",
      block_condition));
  CHECK_THAT(column, lab_catch::StartsWith("a check failed in hold_pinned "
                                           "(tasks/task5_fabric/pins.cpp, line 8): an index out "
                                           "of range: .col(j) was given a column"));
  const std::string row = explain_sanitizer_report(failed(
      "Block.h:120",
      "Eigen::Block<XprType, BlockRows, BlockCols, InnerPanel>::Block(XprType&, Eigen::Index) "
      "[with XprType = Eigen::Matrix<double, 2, -1>; int BlockRows = 1; int BlockCols = -1; bool "
      "InnerPanel = false; Eigen::Index = long int]",
      block_condition));
  CHECK_THAT(row, lab_catch::Contains(".row(i) was given a row the matrix does not have"));
  const std::string element = explain_sanitizer_report(failed(
      "DenseCoeffsBase.h:425", "Scalar& operator()(Eigen::Index)", "index >= 0 && index < size()"));
  CHECK_THAT(element, lab_catch::Contains("an element [i] or (i) outside the vector"));
  const std::string sizes = explain_sanitizer_report(
      failed("CwiseBinaryOp.h:116", "CwiseBinaryOp(const Lhs&, const Rhs&)",
             "aLhs.rows() == aRhs.rows() && aLhs.cols() == aRhs.cols()"));
  CHECK_THAT(sizes, lab_catch::Contains("two matrices of different sizes"));
  for (const std::string& words : {column, row, element, sizes}) {
    CHECK_THAT(words, !lab_catch::Contains("xpr") && !lab_catch::Contains("eigen3") &&
                          !lab_catch::Contains("Assertion") && !lab_catch::Contains("aLhs"));
  }
  // macOS's and Windows' assert() lines, as springlab-check reads them there.
  CHECK_THAT(assertion_text("Assertion failed: (index >= 0 && index < size()), function "
                            "operator(), file DenseCoeffsBase.h, line 410.\n"),
             lab_catch::StartsWith("an index out of range: an element [i] or (i)"));
  CHECK(assertion_text("Assertion failed: n > 0, file a.cpp, line 3\n") ==
        "an assert() failed: n > 0");
  CHECK(assertion_text("nothing failed\n").empty());
  // The line itself leaves what the code printed; the code's own lines stay.
  CHECK(without_assertion_lines("mine\nworker: /usr/include/eigen3/Eigen/src/Core/Block.h:120: "
                                "f: Assertion `i<xpr.cols()' failed.\nAddressSanitizer:"
                                "DEADLYSIGNAL\nalso mine\n") == "mine\nalso mine\n");
  // A student's own assert() keeps its condition: it is theirs.
  CHECK(explain_sanitizer_report("worker: /w/tasks/task1_two_masses/a.cpp:9: void f(): "
                                 "Assertion `length > 0' failed.\n") ==
        "a check failed: an assert() failed: length > 0");
}

TEST_CASE("A failure's Catch2 form (raw lines) is left out unless an instructor asks for it",
          "[verdict]") {
  const std::string message =
      "checked: equation (1.1)\ngot:      7.8\nexpected: 6\nraw: tests/task1.cpp:40: CHECK(x)\n"
      "raw: with values: 7.8 == 6";
  CHECK(without_raw_lines(message) == "checked: equation (1.1)\ngot:      7.8\nexpected: 6");
  CHECK(without_raw_lines("a\nraw: b\nc\n") == "a\nc\n");
  CHECK(without_raw_lines("the code under test stopped") == "the code under test stopped");
  CHECK(without_raw_lines("").empty());
}
