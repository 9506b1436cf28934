#define CATCH_CONFIG_RUNNER
#include "catch_runner.hpp"

#include <catch2/catch.hpp>

#include <cctype>

namespace springlab::grading {
namespace {

// Catch2 reads a test spec as patterns: commas, brackets, quotes, wildcards and backslashes
// mean something there. A backslash makes the next character literal.
std::string literal_spec(const std::string& name) {
  std::string spec;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != ' ') spec += '\\';
    spec += c;
  }
  return spec;
}

}  // namespace

std::string list_tests() {
  Catch::Session session;
  const Catch::Config config(session.configData());
  std::string listing;
  for (const Catch::TestCase& test : Catch::getAllTestCasesSorted(config)) {
    for (const std::string& tag : test.getTestCaseInfo().tags)
      listing += "[" + tag + "]";
    listing += "\t" + test.getTestCaseInfo().name + "\n";
  }
  return listing;
}

void run_test_named(const std::string& name) {
  Catch::Session session;
  session.configData().reporterName = "record";
  session.configData().testsOrTags = {literal_spec(name)};
  session.run();
}

}  // namespace springlab::grading
