#include "reports.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iomanip>
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

std::string xml(const std::string& text) {
  std::string out;
  for (const char c : printable(text)) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\t':
        out += "&#9;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string csv(std::string field) {
  // A spreadsheet would run a name such as =1+2 as a formula: a leading quote keeps it text.
  if (!field.empty() && std::string("=+-@").find(field.front()) != std::string::npos)
    field.insert(0, "'");
  if (field.find_first_of(",\"\n\r") == std::string::npos) return field;
  std::string quoted = "\"";
  for (const char c : field)
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string results_folder(const std::string& name) {
  // One folder per name whatever the names: a name that could clash with the grader's own files
  // (or with a name so made) gets the prefix, and no other name starts with it.
  const std::string prefix = "submission-";
  const bool clash = name.empty() || name.front() == '.' || name.rfind("gradebook.csv", 0) == 0 ||
                     name.rfind("review.csv", 0) == 0 || name.rfind(prefix, 0) == 0;
  return clash ? prefix + name : name;
}

void write_file(const fs::path& file, const std::string& text) {
  const fs::path partial = file.string() + ".partial." + std::to_string(::getpid());
  const auto fail = [&](int error) {
    ::unlink(partial.c_str());
    throw std::runtime_error("cannot write " + escaped(file.string()) + ": " +
                             std::strerror(error));
  };
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(errno);
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      fail(error);
    }
    done += std::size_t(n);
  }
  if (::close(fd) != 0) fail(errno);
  if (::rename(partial.c_str(), file.c_str()) != 0) fail(errno);
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

std::string task_feedback(const SubmissionResult& result, int task, const Kit& kit) {
  const TaskResult& r = result.tasks.at(task);
  std::ostringstream out;
  out << "==> Task " << task << ": the code in tasks/" << kit.task_folder(task)
      << "/ (handout section " << task << ")\n";
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

std::string summary_feedback(const SubmissionResult& result) {
  std::ostringstream out;
  out << "==> Summary: " << points_text(result.points()) << " of "
      << points_text(result.max_points()) << " points\n";
  for (const std::string& note : result.submission.notes)
    out << "  note: " << printable(note) << '\n';
  for (const auto& [task, r] : result.tasks) {
    out << "  task " << task << ": ";
    if (r.problem.rfind("does not compile", 0) == 0)
      out << "does not compile (0 of " << points_text(r.max_points()) << " points)\n";
    else if (!r.problem.empty())
      out << printable(without_colon(r.problem.substr(0, r.problem.find('\n')))) << " (0 of "
          << points_text(r.max_points()) << " points)\n";
    else
      out << state_text(r) << '\n';
  }
  return out.str();
}

std::string feedback(const SubmissionResult& result, const Kit& kit) {
  std::string text;
  for (const auto& [task, r] : result.tasks)
    text += task_feedback(result, task, kit);
  return text + summary_feedback(result);
}

SubmissionResult visible_part(const SubmissionResult& result) {
  SubmissionResult visible = result;
  for (auto& [task, r] : visible.tasks)
    std::erase_if(r.tests, [](const TestResult& t) { return t.test->hidden; });
  return visible;
}

std::string results_json(const SubmissionResult& result, double seconds) {
  using nlohmann::json;
  json tests = json::array();
  for (const auto& [task, r] : result.tasks)
    for (const TestResult& t : r.tests) {
      std::string output;
      if (!r.notes.empty())
        for (const std::string& note : r.notes)
          output += "note: " + printable(note) + "\n";
      if (!r.problem.empty())
        output += printable(r.problem);
      else if (!t.passed)
        output += failure_text(t, 8192);
      const std::string own = "task" + std::to_string(task);
      json tags = json::array({own});
      for (const std::string& tag : t.test->tags)
        if (tag != own) tags.push_back(tag);
      if (t.test->hidden && std::find(tags.begin(), tags.end(), "hidden") == tags.end())
        tags.push_back("hidden");
      tests.push_back({{"name", "Task " + std::to_string(task) + ": " + t.test->name},
                       {"number", std::to_string(task) + "." + std::to_string(t.test->number)},
                       {"score", t.passed ? t.test->points : 0.0},
                       {"max_score", t.test->points},
                       {"status", t.passed ? "passed" : "failed"},
                       {"output", output},
                       {"tags", tags},
                       {"visibility", t.test->hidden ? "after_due_date" : "visible"}});
    }
  // Gradescope shows the run's output at once: it must not tell how the hidden tests went; and
  // what was missing or left out must be said there too, not only in each of the task's tests.
  const SubmissionResult visible = visible_part(result);
  std::size_t hidden = 0;
  double hidden_points = 0.0;
  for (const auto& [task, r] : result.tasks)
    for (const TestResult& t : r.tests)
      if (t.test->hidden) ++hidden, hidden_points += t.test->points;
  std::string output = summary_feedback(visible);
  if (hidden > 0)
    output += "  and " + std::to_string(hidden) + " hidden test" + (hidden == 1 ? "" : "s") + " (" +
              points_text(hidden_points) + " points), shown after the due date\n";
  std::string notes;
  for (const auto& [task, r] : result.tasks)
    for (const std::string& note : r.notes)
      notes += "  task " + std::to_string(task) + ": " + printable(note) + '\n';
  if (!notes.empty()) output += "Notes on the files submitted:\n" + notes;
  const json results = {{"score", std::round(result.points() * 100.0) / 100.0},
                        {"execution_time", long(std::lround(seconds))},
                        {"output", output},
                        {"visibility", "visible"},
                        {"stdout_visibility", "hidden"},
                        {"tests", tests}};
  return results.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

std::string junit_report(const SubmissionResult& result, int task) {
  const TaskResult& r = result.tasks.at(task);
  const std::size_t failures = r.tests.size() - std::size_t(r.passed());
  std::ostringstream out;
  out << std::fixed << std::setprecision(3);
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"springlab " << xml(result.submission.name) << "\" tests=\""
      << r.tests.size() << "\" failures=\"" << failures << "\">\n"
      << "  <testsuite name=\"task" << task << "\" tests=\"" << r.tests.size() << "\" failures=\""
      << failures << "\">\n";
  for (const TestResult& t : r.tests) {
    out << "    <testcase classname=\"springlab.task" << task << "\" name=\"" << xml(t.test->name)
        << "\" time=\"" << t.seconds << "\">\n";
    if (!t.passed) {
      const std::string text = r.problem.empty() ? failure_text(t, 8192) : r.problem;
      out << "      <failure message=\"" << xml(t.message.substr(0, t.message.find('\n'))) << "\">"
          << xml(text) << "</failure>\n";
    }
    out << "    </testcase>\n";
  }
  out << "  </testsuite>\n</testsuites>\n";
  return out.str();
}

std::string review_list(const std::vector<SubmissionResult>& results,
                        const std::string& grader_note) {
  std::string text;
  for (const SubmissionResult& r : results)
    for (const auto& [task, result] : r.tasks) {
      std::string calls;
      for (const std::string& note : result.review)
        calls += (calls.empty() ? "" : "; ") + note;
      if (!calls.empty())
        text += csv(printable(r.submission.name)) + "," + std::to_string(task) + "," + csv(calls) +
                "\n";
    }
  if (!grader_note.empty()) text += "(every submission),," + csv(grader_note) + "\n";
  return text.empty() ? "" : "submission,task,calls\n" + text;
}

std::string gradebook(const std::vector<SubmissionResult>& results) {
  std::string text = "submission,task1,task2,task3,task4,task5,total\n";
  for (const SubmissionResult& r : results) {
    text += csv(printable(r.submission.name));
    for (int task = 1; task <= 5; ++task) {
      const auto it = r.tasks.find(task);
      text += "," + (it == r.tasks.end() ? std::string() : points_text(it->second.points()));
    }
    text += "," + points_text(r.points()) + "\n";
  }
  return text;
}

}  // namespace springlab::grader
