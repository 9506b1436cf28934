// A Catch2 reporter for students (`./lab test taskN --student`): one line per test ending in pass
// or FAIL, and for a failing test only its first failure, with the equation it checks and the
// values involved.
// Linked into every test program; choose it with `-r springlab`.
#define CATCH_CONFIG_EXTERNAL_INTERFACES  // the reporter base classes
#include <catch2/catch.hpp>

#include <algorithm>
#include <ostream>
#include <string>

namespace {

class FeedbackReporter : public Catch::StreamingReporterBase<FeedbackReporter> {
 public:
  using StreamingReporterBase::StreamingReporterBase;

  static std::string getDescription() {
    return "One line per test; the first failure of each failing test, explained";
  }

  void assertionStarting(const Catch::AssertionInfo&) override {}

  bool assertionEnded(const Catch::AssertionStats& stats) override {
    const Catch::AssertionResult& result = stats.assertionResult;
    if (result.isOk() || !first_failure_.empty()) return true;
    const bool threw = result.getResultType() == Catch::ResultWas::ThrewException;
    std::string file = result.getSourceInfo().file;
    file = file.substr(std::min(file.size(), file.rfind("tests/")));  // as the kit names it
    std::string text = threw ? result.getMessage()
                             : file + ":" + std::to_string(result.getSourceInfo().line) + ": " +
                                   result.getExpression();
    if (!threw && result.hasExpandedExpression())
      text += "\n        with values: " + result.getExpandedExpression();
    // A task not written yet needs no more than its message; other failures get the INFO
    // (which equation) and CAPTURE (which values) lines of the test.
    if (text.find("is not implemented yet") == std::string::npos)
      for (const Catch::MessageInfo& message : stats.infoMessages)
        if (message.message != result.getMessage()) text += "\n        " + message.message;
    first_failure_ = text;
    return true;
  }

  // The name goes out before the test runs, so that a test that crashes is still named.
  void testCaseStarting(const Catch::TestCaseInfo& info) override {
    StreamingReporterBase::testCaseStarting(info);
    first_failure_.clear();
    stream << "  " << info.name << " ... " << std::flush;
  }

  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    const bool passed = stats.totals.assertions.failed == 0 && stats.totals.assertions.passed > 0;
    ++(passed ? passed_ : failed_);
    stream << (passed ? "pass" : "FAIL") << '\n';
    if (!passed)
      stream << "        " << (first_failure_.empty() ? "no assertion ran" : first_failure_)
             << '\n';
    stream.flush();  // a crash in the next test must not swallow this one's line
    StreamingReporterBase::testCaseEnded(stats);
  }

  void testRunEnded(const Catch::TestRunStats& stats) override {
    stream << '\n'
           << passed_ << " of " << passed_ + failed_ << " tests pass"
           << (failed_ == 0 ? "." : "; fix the first FAIL above first, then run again.") << '\n';
    StreamingReporterBase::testRunEnded(stats);
  }

 private:
  std::string first_failure_;
  int passed_ = 0, failed_ = 0;
};

}  // namespace

CATCH_REGISTER_REPORTER("springlab", FeedbackReporter)
