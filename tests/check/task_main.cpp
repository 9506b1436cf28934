// springlab-check-taskN's main: task N's public tests against the student's own files, run by
// springlab-check one test per process (see check.cpp), or by CTest (Catch2's own command line).
//   --springlab-list FILE              every test of task N, "[tags]<TAB>name" per line, to FILE
//   --springlab-test INDEX FILE        runs the INDEX-th test of that list (from 0) and writes
//                                      "pass" or "fail", then its first failure explained, to FILE
// Tests are picked by their place in the list, never by a name on a command line: no shell or
// console reads a test's name.
#include "catch_runner.hpp"
#include "reporter.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr int checked_task = SPRINGLAB_CHECK_TASK;

std::vector<std::string> test_names() {
  std::istringstream lines(springlab::grading::list_tests(checked_task));
  std::vector<std::string> names;
  for (std::string line; std::getline(lines, line);)
    if (const auto tab = line.find('\t'); tab != std::string::npos)
      names.push_back(line.substr(tab + 1));
  return names;
}

int run_one(const std::string& index_text, const std::string& file) {
  const std::vector<std::string> names = test_names();
  const long index = std::strtol(index_text.c_str(), nullptr, 10);
  if (index < 0 || index >= long(names.size())) return 2;
  springlab::grading::run_test_named(names[std::size_t(index)]);
  const springlab::grading::TestOutcome& outcome = springlab::grading::test_outcome();
  std::ofstream out(file, std::ios::binary);
  out << (outcome.cases_run == 1 && outcome.passed() ? "pass" : "fail") << '\n'
      << outcome.first_failure;
  out.close();
  return out ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (argc == 3 && mode == "--springlab-list") {
    std::ofstream out(argv[2], std::ios::binary);
    out << springlab::grading::list_tests(checked_task);
    out.close();
    return out ? 0 : 2;
  }
  if (argc == 4 && mode == "--springlab-test") return run_one(argv[2], argv[3]);
  return springlab::grading::run_catch_main(argc, argv);
}
