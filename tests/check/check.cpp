// springlab-check: a student's check of their own tasks where the grader cannot run (it needs
// Linux's sandbox: macOS, Windows). ./lab test runs it there; it prints what grading prints, in
// the same words (tests/feedback/words.hpp) and with the same points (tests/points.toml): a
// block per task, a line per test, the first failure of each failing test explained, and the
// summary. Each test runs in a process of its own (the task's program, task_main.cpp), so a
// crash or an endless loop ends that test only. Nothing here is a grade: the student's own
// machine runs the student's own code, trusted; grading runs every test in the sandbox.
//   springlab-check [--points FILE] [TASK...]     TASK: 1-5 (default: every task)
// Exit status: 0 when every test passes, 1 when one fails, 2 on bad usage.
#include "check_programs.hpp"  // generated: each task's program, folder, points and work folder
#include "points.hpp"
#include "usage_error.hpp"
#include "words.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#ifdef _WIN32
#include <cstdlib>
#else
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace fs = std::filesystem;
using namespace springlab::grader;

namespace {

constexpr double time_limit = 60.0;             // s a test may take
constexpr std::size_t output_kept = 64 * 1024;  // bytes of a test's output kept
constexpr long output_limit_mb = 64;            // MB a test may print (where limits exist)

// How a test process ended.
struct Ended {
  bool started = false;
  bool timed_out = false;
  int exit_status = -1;  // when it exited
  int signal = 0;        // when a signal ended it
};

#ifdef _WIN32
std::string quoted(const std::string& text) {
  return "\"" + text + "\"";
}

// Windows: the console runs it (no time limit: Ctrl-C stops a test that never returns).
Ended run(const std::vector<std::string>& argv, const fs::path& output) {
  std::string command = quoted(argv[0]);
  for (std::size_t i = 1; i < argv.size(); ++i)
    command += " " + quoted(argv[i]);
  command = "\"" + command + " > " + quoted(output.string()) + " 2>&1\"";
  Ended e;
  e.started = true;
  e.exit_status = std::system(command.c_str());
  return e;
}
#else
// POSIX (macOS, Linux): a child with its output in a file, stopped at the time limit.
Ended run(const std::vector<std::string>& argv, const fs::path& output) {
  Ended e;
  const pid_t pid = fork();
  if (pid < 0) return e;
  if (pid == 0) {
    const int fd = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) _exit(127);
    dup2(fd, 1);
    dup2(fd, 2);
    const rlimit printed{rlim_t(output_limit_mb) << 20, rlim_t(output_limit_mb) << 20};
    setrlimit(RLIMIT_FSIZE, &printed);
    std::vector<char*> args;
    for (const std::string& a : argv)
      args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  e.started = true;
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    const std::chrono::duration<double> waited = std::chrono::steady_clock::now() - start;
    if (waited.count() > time_limit) {
      e.timed_out = true;
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) e.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
  return e;
}
#endif

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string seconds_text(double s) {
  std::ostringstream out;
  out << s << " s";
  return out.str();
}

// Why a test that did not finish failed, in the grader's words where it has the same facts;
// `printed`: what its code printed, which holds a failed assert()'s line.
std::string ending_text(const Ended& e, const std::string& printed) {
  if (!e.started) return "the check could not start the test";
  if (const std::string check = assertion_text(printed); !check.empty() && !e.timed_out)
    return "a check failed: " + check;
  if (e.timed_out) return timed_out_text(seconds_text(time_limit), seconds_text(time_limit));
#ifdef SIGXFSZ
  if (e.signal == SIGXFSZ) return output_limit_text(long(output_limit_mb));
#endif
  if (e.signal != 0) return "crashed: " + signal_text(e.signal);
  return early_exit_text(std::to_string(e.exit_status));
}

TestResult run_test(const TestInfo& test, int index, int task, const fs::path& work) {
  const fs::path record = work / ("task" + std::to_string(task) + "-" + std::to_string(index));
  const fs::path output = record.string() + ".out";
  fs::remove(record);
  const Ended e = run(
      {check_programs.at(task).program, "--springlab-test", std::to_string(index), record.string()},
      output);
  TestResult t;
  t.test = &test;
  const std::string printed = read_file(output);
  t.printed_bytes = printed.size();
  t.printed = printed.substr(0, output_kept);
  const std::string verdict = read_file(record);
  if (e.started && !e.timed_out && e.signal == 0 && e.exit_status == 0 && !verdict.empty()) {
    const auto newline = verdict.find('\n');
    t.passed = verdict.compare(0, newline, "pass") == 0;
    t.message = without_raw_lines(newline == std::string::npos ? "" : verdict.substr(newline + 1));
    if (!t.passed && t.message.empty()) t.message = "no check ran";
  } else {
    t.message = ending_text(e, printed);
    if (t.message.rfind("a check failed", 0) == 0) {
      const std::string kept = without_assertion_lines(t.printed);
      t.printed_bytes -= t.printed.size() - kept.size();
      t.printed = kept;
    }
  }
  return t;
}

// Every test of every task whose program is built, with its points.
std::vector<TestInfo> all_tests(const fs::path& points, const fs::path& work) {
  std::string listing;
  for (const auto& [task, p] : check_programs) {
    if (!fs::exists(p.program)) continue;
    const fs::path list = work / ("task" + std::to_string(task) + ".list");
    const Ended e = run({p.program, "--springlab-list", list.string()}, work / "list.out");
    if (e.exit_status != 0)
      throw std::runtime_error("cannot list the tests of task " + std::to_string(task) + " (" +
                               p.program + "): " + ending_text(e, ""));
    listing += read_file(list);
  }
  std::vector<TestInfo> tests = parse_test_list(listing);
  assign_points(tests, points);
  return tests;
}

int check(const std::vector<int>& tasks, const fs::path& points) {
  const fs::path work = check_work_folder;
  fs::remove_all(work);
  fs::create_directories(work);
  const std::vector<TestInfo> tests = all_tests(points, work);
  std::map<int, TaskResult> results;
  for (const int task : tasks) {
    TaskResult& r = results[task];
    r.task = task;
    int index = 0;
    for (const TestInfo* test : tests_of_task(tests, task, false))
      r.tests.push_back(run_test(*test, index++, task, work));
    std::cout << task_text(r, task, check_programs.at(task).folder) << std::flush;
  }
  double points_got = 0.0, points_max = 0.0;
  bool all_passed = true;
  for (const auto& [task, r] : results) {
    points_got += r.points();
    points_max += r.max_points();
    all_passed = all_passed && r.passed() == int(r.tests.size()) && !r.tests.empty();
  }
  std::cout << "==> Summary: " << points_text(points_got) << " of " << points_text(points_max)
            << " points\n";
  for (const auto& [task, r] : results)
    std::cout << "  task " << task << ": " << summary_line(r) << '\n';
  return all_passed ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    fs::path points = check_points_file;
    std::vector<int> tasks;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--points" && i + 1 < argc) {
        points = argv[++i];
      } else if (arg.size() == 1 && check_programs.count(arg[0] - '0') > 0) {
        tasks.push_back(arg[0] - '0');
      } else {
        throw UsageError("springlab-check: unknown argument '" + printable(arg) +
                         "': give task numbers (1-5) and optionally --points FILE");
      }
    }
    if (tasks.empty())
      for (const auto& [task, p] : check_programs)
        tasks.push_back(task);
    for (const int task : tasks)
      if (!fs::exists(check_programs.at(task).program))
        throw UsageError("springlab-check: task " + std::to_string(task) +
                         "'s check is not built: " + check_programs.at(task).program);
    return check(tasks, points);
  } catch (const UsageError& error) {
    std::cerr << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "springlab-check: " << error.what() << '\n';
    return 2;
  }
}
