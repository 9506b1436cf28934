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

std::string task_feedback(const SubmissionResult& result, int task, const Kit& kit) {
  return task_text(result.tasks.at(task), task, kit.task_folder(task));
}

std::string summary_feedback(const SubmissionResult& result) {
  std::ostringstream out;
  out << "==> Summary: " << points_text(result.points()) << " of "
      << points_text(result.max_points()) << " points\n";
  for (const std::string& note : result.submission.notes)
    out << "  note: " << printable(note) << '\n';
  for (const auto& [task, r] : result.tasks) {
    out << "  task " << task << ": " << summary_line(r) << '\n';
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
