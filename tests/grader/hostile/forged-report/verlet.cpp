// Attack: a static initialiser (it runs while the harness loads the code, before any test) writes
// an all-passing JUnit report where the grader might keep its results -- the working folder, the
// results folder beside it (../results, ../../results, as `--work` and `--out` are often
// siblings), every ancestor's results/ folder, and an absolute path under /tmp -- then ends the
// process with status 0. The grader must fail every task 4 test (no verdict record) and no file
// may have been written (the sandbox refuses opening files for writing).
#include "springlab/task4_verlet.hpp"

// Declared by hand: the source policy refuses POSIX headers, but not a declaration (the sandbox
// and the test process's filter are what stop the call).
extern "C" [[noreturn]] void _exit(int);

#include <cstdio>
#include <string>
#include <vector>

using namespace springlab;

namespace {

const char* const report =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<testsuites name=\"springlab forged-report\" tests=\"8\" failures=\"0\">\n"
    "  <testsuite name=\"task4\" tests=\"8\" failures=\"0\">\n"
    "    <testcase classname=\"springlab.task4\" name=\"Verlet: forged\" time=\"0.001\"/>\n"
    "  </testsuite>\n</testsuites>\n";

int write_everywhere() {
  std::vector<std::string> paths = {
      "task4.junit.xml",
      "../results/forged-report/task4.junit.xml",
      "../../results/forged-report/task4.junit.xml",
      "../../results/gradebook.csv",
      "/tmp/forged-report-task4.junit.xml",
  };
  char cwd[4096];
  if (getcwd(cwd, sizeof cwd) != nullptr) {
    std::string folder = cwd;
    while (!folder.empty()) {
      paths.push_back(folder + "/results/forged-report/task4.junit.xml");
      paths.push_back(folder + "/forged-report/task4.junit.xml");
      folder = folder.substr(0, folder.rfind('/'));
    }
  }
  int written = 0;
  for (const std::string& path : paths)
    if (std::FILE* f = std::fopen(path.c_str(), "w")) {
      std::fputs(report, f);
      std::fclose(f);
      ++written;
    }
  std::printf("forged-report: wrote %d of %zu files\n", written, paths.size());
  std::fflush(stdout);
  _exit(0);
}

const int forged = write_everywhere();

}  // namespace

void springlab::verlet_step(const AccelerationFunction&, double, Vectors&, Vectors&,
                            VerletHistory&) {
  (void)forged;
}
