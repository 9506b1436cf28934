#include "sanitizer.hpp"

#include "words.hpp"

#include <sstream>
#include <vector>

namespace springlab::grader {
namespace {

struct Frame {
  std::string function, place;
};

// "    #3 0x55d0 in springlab::submission::f(int) /w/x/tasks/task2_four_masses/a.cpp:13:7"
std::vector<Frame> frames_of(const std::string& report) {
  std::vector<Frame> frames;
  std::istringstream lines(report);
  std::string line;
  while (std::getline(lines, line)) {
    const auto hash = line.find_first_not_of(' ');
    const auto in = line.find(" in ");
    const auto last_space = line.rfind(' ');
    if (hash == std::string::npos || line[hash] != '#' || in == std::string::npos ||
        last_space <= in + 3)
      continue;
    frames.push_back({line.substr(in + 4, last_space - in - 4), line.substr(last_space + 1)});
  }
  return frames;
}

std::string short_function(std::string name) {
  name = name.substr(0, name.find('('));
  const auto colons = name.rfind("::");
  return colons == std::string::npos ? name : name.substr(colons + 2);
}

// "/w/x/tasks/task2_four_masses/a.cpp:13:7" -> "tasks/task2_four_masses/a.cpp, line 13"; "" when
// the place is not in a submission's task folder.
std::string student_place(const std::string& place) {
  const auto at = place.find("tasks/task");
  if (at == std::string::npos) return "";
  const std::string rest = place.substr(at);
  const auto colon = rest.find(':');
  if (colon == std::string::npos) return rest;
  const std::string line = rest.substr(colon + 1, rest.find(':', colon + 1) - colon - 1);
  return rest.substr(0, colon) + ", line " + line;
}

// Where, in words: the student's first frame, or the kit's code the student's data reached.
std::string where(const std::string& report) {
  const std::vector<Frame> frames = frames_of(report);
  for (const Frame& f : frames)
    if (const std::string place = student_place(f.place); !place.empty())
      return " in " + short_function(f.function) + " (" + place + ")";
  for (const Frame& f : frames)
    if (f.function.find("springlab::") != std::string::npos)
      return " in the kit's " + short_function(f.function) +
             ", working on what your code gave it (springs, indices or sizes?)";
  return "";
}

// "reads 8 bytes" from "READ of size 8 at ...".
std::string access(const std::string& report) {
  for (const std::string kind : {"READ", "WRITE"}) {
    const auto at = report.find(kind + " of size ");
    if (at == std::string::npos) continue;
    const auto digits = at + kind.size() + 9;
    const std::string size = report.substr(digits, report.find(' ', digits) - digits);
    return (kind == "READ" ? "reads " : "writes ") + size + " bytes";
  }
  return "accesses memory";
}

std::string line_after(const std::string& text, std::size_t at) {
  return text.substr(at, text.find('\n', at) - at);
}

}  // namespace

std::string explain_sanitizer_report(const std::string& output) {
  // UndefinedBehaviorSanitizer: "FILE:LINE:COLUMN: runtime error: WHAT".
  if (const auto at = output.find(": runtime error: "); at != std::string::npos) {
    const auto start = output.rfind('\n', at) + 1;  // npos + 1 == 0 on the first line
    const std::string place = student_place(output.substr(start, at - start));
    return "undefined behaviour" + (place.empty() ? "" : " (" + place + ")") + ": " +
           line_after(output, at + 17);
  }
  // A failed assertion (Eigen's index and size checks), with the sanitizer's stack after it.
  if (const std::string words = assertion_text(output); !words.empty())
    return "a check failed" + where(output) + ": " + words;
  const std::string marker = "ERROR: AddressSanitizer: ";
  const auto at = output.find(marker);
  if (at == std::string::npos) return "";
  const std::string report = output.substr(at);
  const std::string heading = line_after(report, marker.size());
  const std::string kind = heading.substr(0, heading.find(' '));
  const std::string place = where(report);
  if (kind == "heap-buffer-overflow" || kind == "global-buffer-overflow") {
    // "0 bytes to the right of 64-byte region" (GCC 12's AddressSanitizer), "after" (GCC 14's).
    const auto says = [&report](const char* words) {
      return report.find(words) != std::string::npos;
    };
    const bool after = says(" bytes to the right of ") || says(" bytes after ");
    const bool before = says(" bytes to the left of ") || says(" bytes before ");
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
