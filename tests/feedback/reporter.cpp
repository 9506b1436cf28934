// The harness's Catch2 reporter: remembers, for the one test case run, its assertion counts and
// its first failure in a teacher's words: what was checked (the test's INFO, with its equation),
// what is compared (an INFO "compared: ..."), what the code gave and what was expected, the
// mistake a test recognised ("likely mistake: ...") or what it measured ("measured: ..."), the
// values the test varied (CAPTURE).
// Catch2's own form (the test's file, line and expression) follows on lines marked "raw: ", which
// the grader shows only to whoever asks (springlab-grade --raw). It writes nothing: main.cpp sends
// the outcome to the grader as a record.
#include "reporter.hpp"
#include "catch_internals.hpp"
#include "exception_names.hpp"

#include <algorithm>
#include <array>

namespace springlab::grading {

TestOutcome& test_outcome() {
  static TestOutcome outcome;
  return outcome;
}

namespace {

constexpr std::string_view mistake_prefix = "likely mistake: ";
// What a probe measured when no concrete mistake reproduces it: facts, no cause.
constexpr std::string_view measured_prefix = "measured: ";

// An exception that escaped a check, as Catch2 shows it: its type (the kit's or the standard
// library's) and its message, so that a failure can say which type was thrown. A task not written
// yet keeps its message alone.
CATCH_TRANSLATE_EXCEPTION(const std::exception& error) {
  if (testing::is_a<NotImplemented>(error)) return error.what();
  return testing::exception_type(error) + ": " + error.what();
}

// The type a THROWS_AS check names, from its expression "call(), Type".
std::string expected_type(const Catch::AssertionResult& result) {
  const std::string expression = result.getExpression();
  return expression.substr(expression.rfind(", ") + 2);
}

// Got and expected from Catch2's expansion of a comparison ("28 == 4000", or one operand per
// line when long) or of a matcher ("(0.095, 0.48) is within 1e-14 of (0.1, 0.5)"). Empty when
// the expansion has no such shape (a plain `false`).
struct GotExpected {
  std::string got, expected;
};

GotExpected split_expansion(const std::string& expanded) {
  // Matchers first: their words contain no comparison operator.
  if (const auto at = expanded.find(" is within "); at != std::string::npos) {
    const auto of = expanded.find(" of ", at);
    if (of != std::string::npos)
      return {expanded.substr(0, at), expanded.substr(of + 4) + " (to within " +
                                          expanded.substr(at + 11, of - at - 11) + ")"};
  }
  if (const auto are = expanded.find(" are within "); are != std::string::npos) {
    const auto et = expanded.rfind(" and ", are);
    const auto percent = expanded.find("% of each other", are);
    if (et != std::string::npos && percent != std::string::npos)
      return {expanded.substr(0, et), expanded.substr(et + 5, are - et - 5) + " (to within " +
                                          expanded.substr(are + 12, percent - are - 12) + "%)"};
  }
  if (const auto at = expanded.find(" contains: "); at != std::string::npos)
    return {expanded.substr(0, at), "a text containing " + expanded.substr(at + 11)};
  // Comparisons: "lhs op rhs" on one line, or "lhs\nop\nrhs".
  static const std::array<std::pair<std::string_view, std::string_view>, 6> words{
      {{"==", ""},
       {"!=", "anything but "},
       {"<=", "at most "},
       {">=", "at least "},
       {"<", "less than "},
       {">", "more than "}}};
  for (const auto& [op, phrase] : words) {
    for (const std::string& gap : {" " + std::string(op) + " ", "\n" + std::string(op) + "\n"}) {
      const auto at = expanded.find(gap);
      if (at != std::string::npos)
        return {expanded.substr(0, at), std::string(phrase) + expanded.substr(at + gap.size())};
    }
  }
  return {};
}

std::string raw_lines(const Catch::AssertionResult& result) {
  std::string file = result.getSourceInfo().file;
  file = file.substr(std::min(file.size(), file.rfind("tests/")));  // as the kit names it
  std::string text = "raw: " + file + ":" + std::to_string(result.getSourceInfo().line) + ": " +
                     std::string(result.getTestMacroName()) + "(" + result.getExpression() + ")";
  if (result.hasExpandedExpression())
    text += "\nraw: with values: " + result.getExpandedExpression();
  // Every line marked, also those of an expansion Catch2 spreads over several ("lhs\n==\nrhs"):
  // an unmarked one would reach the student as a stray "==".
  for (auto at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 1))
    if (text.compare(at + 1, 5, "raw: ") != 0) text.insert(at + 1, "raw: ");
  return text;
}

// The test's INFO lines (what it checks, and a recognised mistake) and its CAPTURE values.
struct Context {
  std::string checked, compared, mistake, values;
};

Context context_of(const Catch::AssertionStats& stats) {
  Context c;
  for (const Catch::MessageInfo& m : stats.infoMessages) {
    if (m.message.empty() || m.message == std::string(stats.assertionResult.getMessage())) continue;
    if (m.macroName == "CAPTURE") {
      std::string value = m.message;
      if (const auto at = value.find(" := "); at != std::string::npos) value.replace(at, 4, " = ");
      c.values += (c.values.empty() ? "" : ", ") + value;
    } else if (m.message.rfind("compared: ", 0) == 0) {
      c.compared = m.message;  // the innermost: what the failed check compares
    } else if (m.message.rfind(mistake_prefix, 0) == 0 ||
               m.message.rfind(measured_prefix, 0) == 0) {
      if (c.mistake.empty()) c.mistake = m.message;  // a mistake named, or what was measured
    } else {
      c.checked += (c.checked.empty() ? "" : "\n") + m.message;
    }
  }
  return c;
}

std::string explain(const Catch::AssertionStats& stats) {
  const Catch::AssertionResult& result = stats.assertionResult;
  const Context c = context_of(stats);
  std::string text;
  const auto add = [&text](std::string_view label, const std::string& value) {
    if (!value.empty()) text += (text.empty() ? "" : "\n") + std::string(label) + value;
  };
  const std::string macro(result.getTestMacroName());
  if (result.getResultType() == Catch::ResultWas::ThrewException) {
    // A task not written yet needs no more than its message.
    const std::string what(result.getMessage());
    if (what.find("is not implemented yet") != std::string::npos) return what;
    add("checked: ", c.checked);
    if (macro.find("THROWS_AS") != std::string::npos) {
      add("got:      ", "the exception " + what);
      add("expected: ", "the exception " + expected_type(result) + ", not another type");
    } else {
      add("got:      ", "the exception " + what);
      add("expected: ", "no exception: the check needs this call to return");
    }
  } else if (result.getResultType() == Catch::ResultWas::DidntThrowException) {
    add("checked: ", c.checked);
    add("got: ", "no exception");
    add("expected: ", macro.find("THROWS_AS") != std::string::npos
                          ? "the exception " + expected_type(result)
                          : "an exception");
  } else if (result.getResultType() == Catch::ResultWas::ExplicitFailure) {
    add("checked: ", c.checked);
    add("", std::string(result.getMessage()));  // the test's own words: got and expected
  } else {
    add("checked: ", c.checked);
    add("", c.compared);
    const GotExpected values = split_expansion(result.getExpandedExpression());
    if (!values.got.empty()) {
      add("got:      ", values.got);
      add("expected: ", values.expected);
    } else if (c.mistake.empty() && c.compared.empty() &&
               c.checked.find('\n') == std::string::npos) {
      // A condition with no values to show and no words of the test's own on this failure.
      add("got: ", "false, where the check needs " + std::string(result.getExpression()));
    }
  }
  add("", c.mistake);
  add("where: ", c.values);
  add("", raw_lines(result));
  return text;
}

class RecordReporter : public catch_internals::ReporterBase<RecordReporter> {
  using Base = catch_internals::ReporterBase<RecordReporter>;

 public:
  using Base::Base;

  static std::string getDescription() { return "Keeps the outcome for the grader's record"; }

  void assertionStarting(const Catch::AssertionInfo&) override {}

  catch_internals::AssertionEnded assertionEnded(const Catch::AssertionStats& stats) override {
    TestOutcome& outcome = test_outcome();
    if (!stats.assertionResult.isOk() && outcome.first_failure.empty())
      outcome.first_failure = explain(stats);
    return catch_internals::AssertionEnded(true);  // void(true) in Catch2 3
  }

  void testCaseStarting(const Catch::TestCaseInfo& info) override {
    Base::testCaseStarting(info);
    ++test_outcome().cases_run;
  }

  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    test_outcome().assertions_passed += long(stats.totals.assertions.passed);
    test_outcome().assertions_failed += long(stats.totals.assertions.failed);
    Base::testCaseEnded(stats);
  }
};

CATCH_REGISTER_REPORTER("record", RecordReporter)

}  // namespace
}  // namespace springlab::grading
