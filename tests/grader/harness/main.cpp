// springlab-grade-harness: runs one of the kit's tests against one submission's library, for the
// grader (tests/grader/src/). It is the only program in which submission code ever runs.
//   springlab-grade-harness --list            every test: "[tags]<TAB>name", one per line
//   springlab-grade-harness --run NAME LIB    runs test NAME against the library LIB; the grader
//                                             gives the secret on fd 4 and reads records on fd 3
// The records, in order: "loaded" once the library is in (its static initialisers have run),
// then "verdict" ("pass|fail PASSED FAILED" and the first failure, explained) as the very last
// act before _exit(0). A run that ends any other way has no verdict, and the grader fails it.
#include "catch_runner.hpp"
#include "forwarders.hpp"
#include "record.hpp"
#include "reporter.hpp"
#include "sandbox.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

using namespace springlab;
using namespace springlab::grading;

namespace {

[[noreturn]] void end_with(const char* kind, const std::string& payload) {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);  // what the code under test printed reaches the grader first
  write_record(kind, payload);
  _exit(0);
}

int run_test(const std::string& name, const char* library) {
  if (!receive_secret()) return 2;
  if (!forbid_what_tests_never_need())
    end_with("error", std::string("cannot restrict the test process: ") + std::strerror(errno));
  void* handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) end_with("error", std::string("cannot load the code: ") + dlerror());
  using Entry = const Implementation* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, "springlab_submission_implementation"));
  if (entry == nullptr) end_with("error", "the library has no task table");
  use_submission(*entry());
  if (!forbid_new_code()) end_with("error", "cannot restrict the test process after loading");
  write_record("loaded", "");

  run_test_named(name);
  const TestOutcome& outcome = test_outcome();
  if (outcome.cases_run != 1)
    end_with("error", "the test spec selected " + std::to_string(outcome.cases_run) + " tests");
  end_with("verdict", std::string(outcome.passed() ? "pass " : "fail ") +
                          std::to_string(outcome.assertions_passed) + " " +
                          std::to_string(outcome.assertions_failed) + "\n" + outcome.first_failure);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    std::cout << list_tests();
    return 0;
  }
  if (argc == 4 && std::strcmp(argv[1], "--run") == 0) return run_test(argv[2], argv[3]);
  std::cerr
      << "usage: springlab-grade-harness --list | --run NAME LIBRARY (springlab-grade runs it)\n";
  return 2;
}
