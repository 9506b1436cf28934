#include "sanitizer.hpp"

#include <regex>
#include <sstream>
#include <vector>

namespace springlab::grader {
namespace {

struct Frame {
  std::string function, place;
};

// "#3 0x55d0 in springlab::submission::f(int) /work/x/tasks/task2_four_masses/a.cpp:13:7"
std::vector<Frame> frames_of(const std::string& report) {
  static const std::regex frame(R"(^\s*#\d+ 0x[0-9a-f]+ in (.*) (\S+)$)");
  std::vector<Frame> frames;
  std::istringstream lines(report);
  std::string line;
  std::smatch m;
  while (std::getline(lines, line))
    if (std::regex_match(line, m, frame)) frames.push_back({m[1], m[2]});
  return frames;
}

std::string short_function(std::string name) {
  name = name.substr(0, name.find('('));
  const auto colons = name.rfind("::");
  return colons == std::string::npos ? name : name.substr(colons + 2);
}

// Where, in words: the student's first frame, or the kit's code the student's data reached.
std::string where(const std::string& report) {
  const std::vector<Frame> frames = frames_of(report);
  for (const Frame& f : frames) {
    const auto at = f.place.find("/tasks/task");
    if (at == std::string::npos) continue;
    std::string place = f.place.substr(at + 1);
    // file:line:column -> file, line
    const auto first = place.find(':');
    const auto second = place.find(':', first + 1);
    const std::string line = place.substr(first + 1, second - first - 1);
    return " in " + short_function(f.function) + " (" + place.substr(0, first) + ", line " + line +
           ")";
  }
  for (const Frame& f : frames)
    if (f.function.find("springlab::") != std::string::npos)
      return " in the kit's " + short_function(f.function) +
             ", working on what your code gave it (springs, indices or sizes?)";
  return "";
}

std::string access(const std::string& report) {
  static const std::regex size(R"((READ|WRITE) of size (\d+))");
  std::smatch m;
  if (!std::regex_search(report, m, size)) return "accesses memory";
  return std::string(m[1] == "READ" ? "reads " : "writes ") + m[2].str() + " bytes";
}

}  // namespace

std::string explain_sanitizer_report(const std::string& output) {
  static const std::regex asan(R"(ERROR: AddressSanitizer: ([a-zA-Z-]+))");
  static const std::regex ubsan(R"(([^\s:]+):(\d+):\d+: runtime error: ([^\n]*))");
  static const std::regex assertion(R"(Assertion `([^\n]*)' failed)");
  std::smatch m;
  if (std::regex_search(output, m, ubsan)) {
    std::string file = m[1];
    const auto at = file.find("tasks/task");
    if (at != std::string::npos) file = file.substr(at);
    return "undefined behaviour (" + file + ", line " + m[2].str() + "): " + m[3].str();
  }
  if (std::regex_search(output, m, assertion))
    return "a check failed" + where(output) + ": " + m[1].str() +
           (m[1].str().find("index") != std::string::npos ||
                    m[1].str().find("< size") != std::string::npos
                ? " (an index out of range)"
                : "");
  if (!std::regex_search(output, m, asan)) return "";
  const std::string kind = m[1], report = output.substr(std::size_t(m.position(0)));
  const std::string place = where(report);
  if (kind == "heap-buffer-overflow" || kind == "global-buffer-overflow") {
    const bool after = report.find("to the right of") != std::string::npos;
    const bool before = report.find("to the left of") != std::string::npos;
    return "memory error (" + kind + "): your code " + access(report) + " " +
           (after    ? "just past the end of an array (a loop one step too far, or an index out "
                       "of range?)"
            : before ? "before the start of an array (a negative index?)"
                     : "outside an array") +
           place;
  }
  if (kind == "stack-use-after-scope" || kind == "stack-use-after-return")
    return "memory error (" + kind + "): your code " + access(report) +
           " of a value whose lifetime had ended" + place +
           ". With Eigen, `auto x = a + b;` keeps references to temporaries that are gone by the "
           "next line: write the type instead (Vec2 x = a + b;)";
  if (kind == "heap-use-after-free")
    return "memory error (heap-use-after-free): your code " + access(report) +
           " of memory already freed (a reference into a vector that has grown since?)" + place;
  if (kind == "stack-buffer-overflow" || kind == "stack-buffer-underflow")
    return "memory error (" + kind + "): your code " + access(report) +
           " outside a local array or variable" + place;
  if (kind == "SEGV")
    return "memory error: an access to an address your code does not own (a null pointer, or "
           "an index far out of range?)" +
           place;
  if (kind == "stack-overflow") return "the stack overflowed (a recursion without end?)" + place;
  return "memory error (" + kind + ")" + place;
}

}  // namespace springlab::grader
