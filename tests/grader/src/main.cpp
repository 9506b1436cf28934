// springlab-grade: grades any number of submissions in one run, for instructors (./lab grade) and
// for a student's own check (./lab test --student). Exit status: 0 when every submission was
// graded, whatever the scores (with --student: 0 only when every test passes, else 1); 1 when the
// kit itself is broken; 2 for bad usage. See the README's instructor section.
#include "grading.hpp"
#include "kit.hpp"
#include "points.hpp"
#include "reports.hpp"
#include "submission.hpp"

#include <CLI/CLI.hpp>

#include <fcntl.h>
#include <sched.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>

using namespace springlab::grader;

namespace {

constexpr const char* marker = ".springlab-grade";  // marks a folder this program may empty

struct Options {
  std::vector<std::string> submissions;
  fs::path out = SPRINGLAB_GRADER_OUT;
  fs::path work;  // default: beside out
  fs::path points;
  fs::path kit = SPRINGLAB_GRADER_KIT;
  std::vector<int> tasks{1, 2, 3, 4, 5};
  bool student = false;
  bool max_points = false;
  Settings settings;
};

// Empties `folder` for a new run, refusing any folder this program did not make: nothing of an
// earlier run survives, and nothing else is ever deleted. The folder's marker stays, locked until
// this process ends: a second springlab-grade given the same folder is refused instead of emptying
// it under the first one's feet (two terminals, or two tests at once, with one --work).
void prepare(const fs::path& folder) {
  std::error_code error;
  if (fs::exists(folder) && !fs::is_directory(folder))
    throw UsageError(folder.string() + " exists and is not a folder");
  if (fs::exists(folder) && !fs::is_empty(folder) && !fs::exists(folder / marker))
    throw UsageError(folder.string() + " holds files springlab-grade did not write: choose " +
                     "another folder, or empty it yourself");
  fs::create_directories(folder, error);
  if (error) throw UsageError("cannot make " + folder.string() + ": " + error.message());
  const fs::path mark = folder / marker;
  // Kept open (and locked) for the rest of the run; close-on-exec, so no test process holds it.
  const int lock = open(mark.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock < 0)
    throw UsageError("cannot write in " + folder.string() + ": " + std::strerror(errno));
  if (flock(lock, LOCK_EX | LOCK_NB) != 0)
    throw UsageError(folder.string() + " is in use by another springlab-grade run: wait for it " +
                     "to end, or give this run another --out or --work folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename() == marker) continue;
    fs::remove_all(entry.path(), error);
    if (error) throw UsageError("cannot empty " + folder.string() + ": " + error.message());
  }
  const std::string text = "written by springlab-grade, emptied by its next run\n";
  if (ftruncate(lock, 0) != 0 || write(lock, text.data(), text.size()) != ssize_t(text.size()))
    throw UsageError("cannot write in " + folder.string() + ": " + std::strerror(errno));
}

// The processors this process may use: its affinity mask, and a container's CPU quota (a
// container often sees every processor of its host but may use only a few).
int available_processors() {
  cpu_set_t set;
  int count = sched_getaffinity(0, sizeof set, &set) == 0
                  ? CPU_COUNT(&set)
                  : int(std::thread::hardware_concurrency());
  std::string quota;
  long period = 0;
  std::ifstream v2("/sys/fs/cgroup/cpu.max");  // cgroup v2: "QUOTA PERIOD" or "max PERIOD"
  std::ifstream v1_quota("/sys/fs/cgroup/cpu/cpu.cfs_quota_us");  // cgroup v1: -1 for none
  std::ifstream v1_period("/sys/fs/cgroup/cpu/cpu.cfs_period_us");
  const bool found = bool(v2 >> quota >> period) || (v1_quota >> quota && v1_period >> period);
  if (found && quota != "max" && quota.front() != '-' && period > 0)
    count = std::min(count, int((std::stol(quota) + period - 1) / period));
  return std::max(1, count);
}

// Grading writes nowhere near a submission: neither inside one, nor around one it would empty.
void check_apart(const fs::path& folder, const std::vector<Submission>& submissions) {
  const fs::path f = fs::weakly_canonical(fs::absolute(folder));
  for (const Submission& s : submissions) {
    const auto inside = [](const fs::path& a, const fs::path& b) {
      const auto [end, _] = std::mismatch(b.begin(), b.end(), a.begin(), a.end());
      return end == b.end();
    };
    if (inside(f, s.folder) || inside(s.folder, f))
      throw UsageError(folder.string() + " and the submission " + s.folder.string() +
                       " overlap: grading never writes in or around a submission");
  }
}

std::string run_trusted(const std::vector<std::string>& argv) {
  ProcessPool pool(1);
  Command c;
  c.argv = argv;
  c.env = plain_environment();
  c.directory = "/";
  c.limits.output_kept = c.limits.output_limit;
  std::string output;
  pool.add(std::move(c), [&](Outcome o) {
    if (!o.exited || o.exit_code != 0)
      throw std::runtime_error(argv.front() + " failed: " + o.start_error + o.output);
    output = std::move(o.output);
  });
  pool.run();
  return output;
}

void write_file(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::vector<Submission> find_all(const Options& options, const Kit& kit) {
  std::vector<Submission> found;
  std::map<std::string, std::string> seen;
  for (const std::string& folder : options.submissions) {
    Submission s = find_submission(folder, kit);
    const auto [it, fresh] = seen.emplace(s.name, folder);
    if (!fresh)
      throw UsageError("two submissions would share the name '" + printable(s.name) +
                       "' in the gradebook: " + printable(it->second) + " and " +
                       printable(folder) + " (rename one folder)");
    found.push_back(std::move(s));
  }
  return found;
}

// An absolute path without a trailing separator: the compiler runs in other folders, and
// "results/" and "results" are the same folder.
fs::path absolute_folder(const fs::path& path) {
  fs::path a = fs::absolute(path).lexically_normal();
  if (a.filename().empty() && a.has_parent_path()) a = a.parent_path();
  return a;
}

int grade(Options options) {
  options.out = absolute_folder(options.out);
  options.work =
      options.work.empty() ? options.out.parent_path() / "work" : absolute_folder(options.work);
  const Kit kit = read_kit(options.kit);
  // The tasks graded, or all for --max-points: a student's check of task 1 may have built the
  // programs of task 1 only (./lab test task1).
  std::string listing;
  for (const auto& [task, program] : kit.programs) {
    if (!options.max_points &&
        std::find(options.tasks.begin(), options.tasks.end(), task) == options.tasks.end())
      continue;
    if (!fs::exists(program))
      throw UsageError(program.string() + " is not built: cmake --build " +
                       options.kit.parent_path().parent_path().parent_path().string() +
                       " --target springlab-grader-task" + std::to_string(task) +
                       " (or springlab-grader, for every task)");
    listing += run_trusted({program.string(), "--list"});
  }
  std::vector<TestInfo> tests = parse_test_list(listing);
  assign_points(tests, options.points.empty() ? kit.points : options.points);
  if (options.max_points) {  // for the GitHub Classroom workflow of a release (./lab release)
    std::map<int, double> max;
    for (const TestInfo& t : tests)
      if (!t.hidden || !options.student) max[t.task] += t.points;
    for (const auto& [task, points] : max)
      std::cout << "task" << task << ' ' << points << '\n';
    return 0;
  }
  if (options.submissions.empty()) throw UsageError("submission is required");
  const std::vector<Submission> submissions = find_all(options, kit);
  for (const Submission& s : submissions)
    if (s.empty())
      std::cerr << "springlab-grade: " << printable(s.name) << ": not one of the tasks' files "
                << "found (graded as the starter code): is " << printable(s.folder.string())
                << " a submission?\n";
  Settings settings = options.settings;
  settings.tasks = options.tasks;
  settings.work = options.work;
  settings.hidden = !options.student;  // a student's check never shows the hidden tests
  check_apart(options.out, submissions);
  check_apart(settings.work, submissions);
  prepare(options.out);
  prepare(settings.work);

  // Whether submission code can have namespaces of its own here: said once, on the terminal and
  // (when it cannot) in review.csv.
  const Isolation isolation = Isolation::probe({kit.root, options.out, settings.work});
  std::cerr << "springlab-grade: " << isolation.describe() << "\n";
  Grader grader(kit, tests, settings, isolation);
  std::cerr << "springlab-grade: the reference's time per test (measured once per build)\n";
  grader.calibrate(options.kit.parent_path() / "calibration.txt");
  if (options.student) {
    std::cerr << "springlab-grade: compiling your code, then running each test in a process of "
              << "its own, plainly and with the sanitizers (which check every memory access)\n";
  } else {
    const auto hidden = std::count_if(tests.begin(), tests.end(), [&](const TestInfo& t) {
      return t.hidden && std::count(options.tasks.begin(), options.tasks.end(), t.task) > 0;
    });
    std::cerr << "springlab-grade: grading " << submissions.size() << " submission"
              << (submissions.size() == 1 ? "" : "s") << " (" << settings.jobs
              << " processes at once; a test may take " << grader.time_limit_text() << ")";
    if (hidden > 0)
      std::cerr << ", hidden tests included (" << hidden << ", shown to students after the due "
                << "date)";
    std::cerr << "\n";
  }

  bool all_passed = true;
  std::size_t finished = 0;
  std::map<std::string, std::set<int>> tasks_done;  // student mode: print tasks in order
  const auto task_done = [&](const SubmissionResult& r, int task) {
    if (!options.student) return;
    std::set<int>& done = tasks_done[r.submission.name];
    done.insert(task);
    for (const int t : options.tasks) {
      if (done.count(t) == 0) break;
      if (done.count(-t) > 0) continue;  // printed already
      std::cout << task_feedback(r, t, kit) << std::flush;
      done.insert(-t);
    }
  };
  const auto submission_done = [&](const SubmissionResult& r) {
    // Its own tests' time, not the batch's: in a batch the submissions share the machine.
    double seconds = 0.0;
    for (const auto& [task, result] : r.tasks)
      for (const TestResult& t : result.tests)
        seconds += t.seconds + t.sanitized_seconds;
    const fs::path folder = options.out / results_folder(r.submission.name);
    fs::create_directories(folder);
    write_file(folder / "feedback.txt", feedback(r, kit));
    write_file(folder / "results.json", results_json(r, seconds));
    for (const auto& [task, result] : r.tasks)
      write_file(folder / ("task" + std::to_string(task) + ".junit.xml"), junit_report(r, task));
    all_passed = all_passed && r.points() == r.max_points();
    ++finished;
    if (options.student) {
      std::cout << summary_feedback(r);
    } else if (submissions.size() == 1) {
      std::cout << feedback(r, kit);
    } else {
      std::cout << "[" << finished << "/" << submissions.size() << "] "
                << printable(r.submission.name) << ": " << points_text(r.points()) << " of "
                << points_text(r.max_points()) << " points" << std::endl;
    }
  };
  const std::vector<SubmissionResult> results =
      grader.grade(submissions, task_done, submission_done);
  write_file(options.out / "gradebook.csv", gradebook(results));
  const std::string review =
      review_list(results, isolation.namespaces() ? "" : isolation.describe());
  if (!review.empty()) write_file(options.out / "review.csv", review);
  if (!options.student) {
    std::cerr << "springlab-grade: " << options.out.string() << "/gradebook.csv, and per "
              << "submission feedback.txt, results.json and taskN.junit.xml\n";
    if (!review.empty())
      std::cerr << "springlab-grade: some code calls what no task needs (ending the program, "
                << "files, threads, ...): " << options.out.string() << "/review.csv lists it\n";
  }
  return options.student && !all_passed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Not dumpable: no process of the same user (a test, where there are no namespaces to hide the
  // grader) may read its environment (the instructor's shell's) or its memory through /proc.
  prctl(PR_SET_DUMPABLE, 0, 0, 0, 0);
  Options options;
  options.settings.jobs = available_processors();
  CLI::App app(
      "springlab-grade: grades submissions of the springlab tasks, each test in a "
      "process of its own under limits, plain and with the sanitizers");
  app.add_option("submission", options.submissions,
                 "a copy of tasks/, a student repository (its tasks/ is used) or a folder of "
                 "the loose .cpp files");
  app.add_option("--out", options.out, "results: gradebook.csv and a folder per submission")
      ->capture_default_str();
  app.add_option("--work", options.work, "private copies and builds (default: beside --out)");
  app.add_option("--jobs", options.settings.jobs,
                 "processes at once (default: the processors this machine or container allows)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--points", options.points, "the points file (default: the kit's)");
  app.add_option("--tasks", options.tasks, "the tasks to grade")
      ->delimiter(',')
      ->check(CLI::Range(1, 5));
  app.add_option("--time-factor", options.settings.time_factor,
                 "a test may take this many times the reference's time")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--time-floor", options.settings.time_floor, "...and at least this many s")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  app.add_option("--memory", options.settings.memory_mb, "MB of memory per test process")
      ->check(CLI::Range(64L, 65536L))
      ->capture_default_str();
  app.add_flag("--student", options.student,
               "a student's check: the feedback on the terminal; exit 1 unless every test passes");
  app.add_flag("--raw", options.settings.raw,
               "for instructors: show each failure's test file, line and expression as Catch2 "
               "states them, after the student's wording");
  app.add_flag("--max-points", options.max_points,
               "print each task's maximum (the sum of its tests' points) and grade nothing");
  app.add_option("--kit", options.kit, "the kit.toml of the build to use")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);
    std::cerr << "springlab-grade: " << error.what() << " (springlab-grade --help lists the "
              << "options)\n";
    return 2;
  }
  std::sort(options.tasks.begin(), options.tasks.end());
  options.tasks.erase(std::unique(options.tasks.begin(), options.tasks.end()), options.tasks.end());
  try {
    return grade(options);
  } catch (const UsageError& error) {
    std::cerr << "springlab-grade: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "springlab-grade: " << error.what() << '\n';
    return 1;
  }
}
