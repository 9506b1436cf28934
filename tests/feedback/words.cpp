#include "words.hpp"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace springlab::grader {
namespace {

constexpr std::size_t printed_in_feedback = 2048;  // bytes of a failing test's output shown

std::string indented(const std::string& text, const std::string& indent) {
  std::istringstream lines(text);
  std::string line, result;
  while (std::getline(lines, line))
    result += indent + line + '\n';
  return result;
}

std::string bytes_text(std::size_t bytes) {
  std::ostringstream out;
  if (bytes < 10000)
    out << bytes << " bytes";
  else if (bytes < (10u << 20))
    out << bytes / 1024 << " KB";
  else
    out << (bytes >> 20) << " MB";
  return out.str();
}

std::string count_text(const TaskResult& r) {
  return std::to_string(r.passed()) + " of " + std::to_string(r.tests.size()) + " tests pass (" +
         points_text(r.points()) + " of " + points_text(r.max_points()) + " points)";
}

// What a task whose every test failed on a starter stub asks for first ("write verlet_step in
// tasks/task4_verlet/verlet.cpp, handout section 4"), from the stub's message ("Task 4 is not
// implemented yet: write ... (see handout section 4)"); "" for a task that was started.
std::string not_started(const TaskResult& r) {
  const std::string marker = " is not implemented yet: ";
  const bool untouched =
      !r.tests.empty() && std::all_of(r.tests.begin(), r.tests.end(), [&](const TestResult& t) {
        return !t.passed && t.message.find(marker) != std::string::npos;
      });
  if (!untouched) return "";
  const std::string& m = r.tests.front().message;
  std::string what = m.substr(m.find(marker) + marker.size());
  what = what.substr(0, what.find('\n'));
  if (const auto see = what.rfind(" (see "); see != std::string::npos && what.back() == ')')
    what = what.substr(0, see) + ", " + what.substr(see + 6, what.size() - see - 7);
  return printable(what);
}

// A problem's first line ends with a colon when its details follow; the summary has none.
std::string without_colon(std::string line) {
  while (!line.empty() && (line.back() == ':' || line.back() == ' '))
    line.pop_back();
  return line;
}

// A task's line in the summary: all pass, not started (what to write first), or the count and
// the first failure.
std::string state_text(const TaskResult& r) {
  const auto failed =
      std::find_if(r.tests.begin(), r.tests.end(), [](const TestResult& t) { return !t.passed; });
  const std::string points =
      " (" + points_text(r.points()) + " of " + points_text(r.max_points()) + " points)";
  if (failed == r.tests.end())
    return (r.tests.size() == 1 ? "its 1 test passes"
                                : "all " + std::to_string(r.tests.size()) + " tests pass") +
           points;
  if (const std::string what = not_started(r); !what.empty()) return "not started (" + what + ")";
  return count_text(r) + "; first failure: " + printable(failed->test->name);
}

}  // namespace

// The explanation of one failed test, with what its code printed (the start of it).
std::string failure_text(const TestResult& t, std::size_t shown) {
  std::string text = printable(t.message) + '\n';
  if (t.printed_bytes > 0) {
    text += "your code printed " + bytes_text(t.printed_bytes) +
            (t.printed_bytes > shown ? ", of which the first " + bytes_text(shown) : "") + ":\n";
    text += indented(printable(t.printed.substr(0, shown)), "| ");
  }
  return text;
}

std::string points_text(double points) {
  std::ostringstream out;
  out << std::round(points * 100.0) / 100.0;
  return out.str();
}

std::string escaped(const std::string& name) {
  const std::string kept = printable(name);  // byte for byte, '?' where a byte was not kept
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7f || (kept[i] == '?' && c != '?')) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(c));
      out += hex;
    } else {
      out += char(c);
    }
  }
  return out;
}

std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      out += (c < 0x20 && c != '\n' && c != '\t') || c == 0x7f ? '?' : char(c);
      ++i;
      continue;
    }
    // A UTF-8 sequence: a lead byte for 2-4 bytes, then continuation bytes 10xxxxxx; no
    // overlong forms, no surrogates (U+D800-DFFF), nothing above U+10FFFF.
    const std::size_t length = c >= 0xf0 && c <= 0xf4 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k)
      valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
    if (valid && length > 2) {
      const auto second = static_cast<unsigned char>(text[i + 1]);
      valid = !(c == 0xe0 && second < 0xa0) && !(c == 0xed && second >= 0xa0) &&
              !(c == 0xf0 && second < 0x90) && !(c == 0xf4 && second >= 0x90);
    }
    if (valid) {
      out.append(text, i, length);
      i += length;
    } else {
      out += '?';
      ++i;
    }
  }
  return out;
}

std::string timed_out_text(const std::string& after, const std::string& limit) {
  return "timed out: stopped after " + after + " (the limit is " + limit + "; an endless loop?)";
}

std::string output_limit_text(long megabytes) {
  return "printed more than " + std::to_string(megabytes) +
         " MB: stopped (printing inside a loop over every step?)";
}

std::string early_exit_text(const std::string& status) {
  return "exited before the test finished (exit status " + status +
         "): does your code call exit(), _exit() or abort()?";
}

std::string signal_text(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "segmentation fault (an invalid memory access: an index out of range, or a null "
             "pointer?)";
#ifdef SIGBUS
    case SIGBUS:
      return "bus error (an invalid memory access)";
#endif
    case SIGFPE:
      return "arithmetic error (an integer division by zero?)";
    case SIGABRT:
      return "aborted (a failed assertion, or an error nothing caught?)";
    case SIGILL:
      return "illegal instruction (a function that returns no value where one is due?)";
    default:
#ifdef _WIN32
      return "signal " + std::to_string(signal);
#else
      return std::string("signal ") + std::to_string(signal) + " (" + strsignal(signal) + ")";
#endif
  }
}

namespace {

bool has(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

// What a failed assert() says, in a student's words (issue 38: no library text, no paths), from
// its `line` (the whole line, which names the file and function) and its `condition`. Eigen's
// checks are told by their file and condition, each the one check of its kind in Eigen 3.4 and 5.
std::string assertion_words(const std::string& line, const std::string& condition) {
  if (has(line, "Block.h") && has(condition, "i<xpr.cols()")) {
    // Block(xpr, i): one column (.col(j)) or one row (.row(i)) of a matrix.
    const bool row = has(line, "BlockRows = 1;") && !has(line, "BlockCols = 1;");
    return row ? "an index out of range: .row(i) was given a row the matrix does not have (Vec2 "
                 "and Vectors have rows 0 and 1 only, x and y)"
               : "an index out of range: .col(j) was given a column the matrix does not have (a "
                 "matrix with n columns has columns 0 to n-1: one per particle in Vectors)";
  }
  if (has(line, "Block.h"))
    return "an index out of range: a block (.block, .segment, .head, .tail, .leftCols, "
           ".middleCols ...) reaches outside the matrix";
  if (has(line, "DenseCoeffsBase.h") && has(condition, "row >= 0"))
    return "an index out of range: an element (i, j) outside the matrix (rows 0 to rows()-1, "
           "columns 0 to cols()-1)";
  if (has(line, "DenseCoeffsBase.h"))
    return "an index out of range: an element [i] or (i) outside the vector (0 to size()-1)";
  if (has(line, "CwiseBinaryOp.h"))
    return "two matrices of different sizes were combined (+, -, cwiseProduct ...): both sides "
           "must have the same rows and columns";
  if (has(line, "Product.h") || has(condition, "lhs.cols() == rhs.rows()"))
    return "a product of matrices whose sizes do not fit (the left one's columns must equal the "
           "right one's rows)";
  if (has(line, "AssignEvaluator.h") || has(line, "PlainObjectBase.h") || has(line, "Assign.h") ||
      has(line, "DenseBase.h"))
    return "a matrix was given a value of another size (a Vec2 or a block assigned from a matrix "
           "of other rows or columns?)";
  if (has(line, "eigen3") || has(line, "Eigen/"))
    return "one of Eigen's checks failed: an index or a size that does not fit the matrix";
  // The student's own assert(): their condition is theirs to read.
  return "an assert() failed: " + condition;
}

}  // namespace

std::string assertion_text(const std::string& output) {
  // glibc: "PROGRAM: FILE:LINE: FUNCTION: Assertion `CONDITION' failed."
  if (const auto at = output.find(": Assertion `"); at != std::string::npos) {
    const auto start = output.rfind('\n', at) + 1;  // npos + 1 == 0 on the first line
    const std::string line = output.substr(start, output.find('\n', at) - start);
    const auto from = line.find(": Assertion `") + 13;
    return assertion_words(line, line.substr(from, line.rfind("' failed") - from));
  }
  // macOS: "Assertion failed: (CONDITION), function F, file FILE, line N."; Windows:
  // "Assertion failed: CONDITION, file FILE, line N".
  if (const auto at = output.find("Assertion failed: "); at != std::string::npos) {
    const std::string line = output.substr(at, output.find('\n', at) - at);
    std::string condition = line.substr(18, line.find(", f") - 18);
    if (condition.size() > 1 && condition.front() == '(' && condition.back() == ')')
      condition = condition.substr(1, condition.size() - 2);
    return assertion_words(line, condition);
  }
  return "";
}

std::string without_assertion_lines(const std::string& printed) {
  std::string kept;
  std::size_t start = 0;
  while (start < printed.size()) {
    const auto end = std::min(printed.find('\n', start), printed.size());
    const std::string line = printed.substr(start, end - start + 1);
    if (line.find(": Assertion `") == std::string::npos &&
        line.rfind("Assertion failed: ", 0) == std::string::npos &&
        line.rfind("AddressSanitizer:DEADLYSIGNAL", 0) != 0)
      kept += line;
    start = end + 1;
  }
  return kept;
}

std::string without_raw_lines(const std::string& message) {
  std::string kept;
  std::size_t start = 0;
  while (start < message.size()) {
    const std::size_t end = std::min(message.find('\n', start), message.size());
    if (message.compare(start, 5, "raw: ") != 0)
      kept.append(message, start, end - start).append("\n");
    start = end + 1;
  }
  if (!kept.empty() && (message.empty() || message.back() != '\n')) kept.pop_back();
  return kept;
}

std::string task_text(const TaskResult& r, int task, const std::string& folder) {
  std::ostringstream out;
  out << "==> Task " << task << ": the code in tasks/" << folder << "/ (handout section " << task
      << ")\n";
  for (const std::string& note : r.notes)
    out << "  note: " << printable(note) << '\n';
  if (!r.problem.empty()) {
    out << indented(printable(r.problem), "  ");
    out << "\n" << count_text(r) << ".\n";
    return out.str();
  }
  if (!r.warnings.empty())
    out << "  the compiler warns (the tests still run):\n"
        << indented(printable(r.warnings), "    ");
  // A task not started: every test stops at the stub, so its message is said once, below.
  const bool untouched = !not_started(r).empty();
  for (const TestResult& t : r.tests) {
    out << "  " << t.test->name << " ... "
        << (t.passed    ? "pass"
            : untouched ? "not started"
                        : "FAIL")
        << (t.test->hidden ? std::string(" ") + hidden_mark : "") << '\n';
    if (!t.passed && !untouched) out << indented(failure_text(t, printed_in_feedback), "        ");
  }
  out << '\n'
      << count_text(r)
      << (r.passed() == int(r.tests.size()) ? "."
          : not_started(r).empty()          ? "; fix the first FAIL above first, then run again."
                                            : "; not started yet: " + not_started(r) + ".")
      << '\n';
  return out.str();
}

std::string summary_line(const TaskResult& r) {
  if (r.problem.rfind("does not compile", 0) == 0)
    return "does not compile (0 of " + points_text(r.max_points()) + " points)";
  if (!r.problem.empty())
    return printable(without_colon(r.problem.substr(0, r.problem.find('\n')))) + " (0 of " +
           points_text(r.max_points()) + " points)";
  return state_text(r);
}

}  // namespace springlab::grader
