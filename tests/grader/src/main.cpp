// springlab-grade: grades any number of submissions in one run, for instructors (./lab grade) and
// for a student's own check (./lab test --student). Exit status: 0 when every submission was
// graded, whatever the scores (with --student: 0 only when every test passes, else 1); 1 when the
// kit itself is broken; 2 for bad usage; 3 when some submissions could not be graded because of
// the grader's own disk, files or processes (the others are); 128 + N when signal N stopped it.
// See the README's instructor section.
#include "grading.hpp"
#include "kit.hpp"
#include "points.hpp"
#include "reports.hpp"
#include "results.hpp"
#include "submission.hpp"

#include <CLI/CLI.hpp>

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>

using namespace springlab::grader;

namespace {

// Where a run's time went, for whoever wonders why a class takes as long as it does (issue 27):
// the processes it started, by kind, and their wall time summed (`--jobs` of them run at once,
// so the sums add up to about that many times the run's own time).
void print_phase_times(const PhaseTimes& phases) {
  std::cerr << "springlab-grade: the processes of this run, by kind (wall time, summed):\n";
  for (const auto& [phase, t] : phases) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-20s %6ld in %8.1f s (%.2f s each)\n", phase.c_str(),
                  t.count, t.wall_seconds, t.wall_seconds / double(t.count));
    std::cerr << line;
  }
}

constexpr const char* marker = ".springlab-grade";  // marks a folder this program may empty

struct Options {
  std::vector<std::string> submissions;
  fs::path out = SPRINGLAB_GRADER_OUT;
  fs::path work;  // default: under the kit's build/grade/work/
  fs::path points;
  fs::path kit = SPRINGLAB_GRADER_KIT;
  std::vector<int> tasks{1, 2, 3, 4, 5};
  bool student = false;
  bool max_points = false;
  bool calibrate = false;
  bool replace = false;
  Settings settings;
};

// Empties the work folder for a new run, refusing any folder this program did not make, and keeps
// it locked until this process ends: a second run given the same folder is refused instead of
// emptying it under the first one's feet.
int take_work_folder(const fs::path& folder) {
  std::error_code error;
  if (fs::exists(folder) && !fs::is_directory(folder))
    throw UsageError(escaped(folder.string()) + " exists and is not a folder");
  if (fs::exists(folder) && !fs::is_empty(folder) && !fs::exists(folder / marker))
    throw UsageError(escaped(folder.string()) + " holds files springlab-grade did not write: " +
                     "choose another folder, or empty it yourself");
  fs::create_directories(folder, error);
  if (error) throw UsageError("cannot make " + escaped(folder.string()) + ": " + error.message());
  const int lock = open((folder / marker).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock < 0)
    throw UsageError("cannot write in " + escaped(folder.string()) + ": " + std::strerror(errno));
  if (flock(lock, LOCK_EX | LOCK_NB) != 0)
    throw UsageError(escaped(folder.string()) + " is in use by another springlab-grade run: " +
                     "wait for it to end, or give this run another --out or --work folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename() == marker) continue;
    fs::remove_all(entry.path(), error);
    if (error)
      throw UsageError("cannot empty " + escaped(folder.string()) + ": " + error.message());
  }
  return lock;
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

bool is_inside(const fs::path& a, const fs::path& b) {
  const auto [end, _] = std::mismatch(b.begin(), b.end(), a.begin(), a.end());
  return end == b.end();
}

// Grading writes nowhere near a submission: neither inside one, nor around one it would empty.
void check_apart(const fs::path& folder, const std::vector<Submission>& submissions) {
  const fs::path f = fs::weakly_canonical(fs::absolute(folder));
  for (const Submission& s : submissions)
    if (!s.folder.empty() && (is_inside(f, s.folder) || is_inside(s.folder, f)))
      throw UsageError(escaped(folder.string()) + " and the submission " +
                       escaped(s.folder.string()) +
                       " overlap: grading never writes in or around a submission");
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

// A submission folder as the grader finds it; one it cannot read is "not graded", with why.
Submission find_one(const std::string& folder, const Kit& kit) {
  try {
    return find_submission(folder, kit);
  } catch (const fs::filesystem_error& error) {
    Submission s;
    s.folder = fs::absolute(folder).lexically_normal();
    s.name = s.folder.filename().string();
    s.fault = "the grader could not read the submission: " + escaped(error.what());
    return s;
  }
}

std::vector<Submission> find_all(const Options& options, const Kit& kit) {
  std::vector<Submission> found;
  std::map<std::string, std::string> seen;
  for (const std::string& folder : options.submissions) {
    Submission s = find_one(folder, kit);
    const auto [it, fresh] = seen.emplace(s.name, folder);
    if (!fresh)
      throw UsageError("two submissions would share the name '" + escaped(s.name) +
                       "' in the gradebook: " + escaped(it->second) + " and " + escaped(folder) +
                       " (rename one folder)");
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

// What a submission's grade depends on in the kit and the settings: its programs, the points,
// the limits, the tasks and whether the hidden tests run.
std::string run_signature(const Kit& kit, const std::vector<TestInfo>& tests,
                          const Settings& settings) {
  std::ostringstream s;
  std::error_code error;
  for (const int task : settings.tasks)
    for (const fs::path& program : {kit.programs.at(task), kit.sanitized_programs.at(task)})
      s << program.string() << ' ' << fs::file_size(program, error) << ' '
        << fs::last_write_time(program, error).time_since_epoch().count() << '\n';
  for (const TestInfo& t : tests)
    s << t.name << ' ' << t.points << ' ' << t.hidden << '\n';
  s << settings.time_factor << ' ' << settings.time_floor << ' ' << settings.memory_mb << ' '
    << settings.hidden << ' ' << settings.raw << '\n';
  return s.str();
}

std::string signature_of(const std::string& run, const Submission& s, const Settings& settings) {
  if (!s.fault.empty()) return "";
  const std::string digest = submission_digest(s, settings.tasks);
  if (digest.empty()) return "";
  return std::to_string(std::hash<std::string>{}(run + digest)) + "-" +
         std::to_string(digest.size());
}

void stop_on_signal(int signal) {
  interrupt(signal);
}

// A line of the reference's measurement (Grader::calibrate's progress), on the terminal.
void say_measuring(const std::string& line) {
  std::cerr << "springlab-grade: " << line << "\n";
}

// The reference's times of --tasks, measured now unless this build's cache has them, and nothing
// graded: run once before gradings that start side by side (the kit's own suite), which would
// otherwise each measure them again. A cache that cannot be written is an error here (exit 1):
// measuring is all this run is for.
int calibrate_only(const Options& options, const Kit& kit, const std::vector<TestInfo>& tests) {
  if (kit.solutions.empty()) {
    std::cerr << "springlab-grade: nothing to measure: this build grades with the reference's "
              << "times shipped with it (" << escaped(kit.calibration.string()) << ")\n";
    return 0;
  }
  Settings settings = options.settings;
  settings.tasks = options.tasks;
  settings.work = options.work;
  const int work_lock = take_work_folder(settings.work);
  const Isolation isolation = Isolation::probe({kit.root, settings.work});
  Grader grader(kit, tests, settings, isolation);
  const fs::path cache = options.kit.parent_path() / "calibration.txt";
  const bool written = grader.calibrate(cache, say_measuring);
  close(work_lock);
  if (!written)
    throw std::runtime_error(
        "--calibrate: the reference's times were measured but could not be kept in " +
        escaped(cache.string()));
  std::cerr << "springlab-grade: the reference's times are in " << escaped(cache.string()) << "\n";
  return 0;
}

// --out made absolute, and --work: under the kit's build/ (ignored by git) whatever the current
// folder, one per results folder, so that two runs with their own --out never share one.
void settle_folders(Options& options, const Kit& kit) {
  options.out = absolute_folder(options.out);
  options.work = options.work.empty()
                     ? kit.root / "build" / "grade" / "work" /
                           std::to_string(std::hash<std::string>{}(options.out.string()) % 1000003)
                     : absolute_folder(options.work);
  if (is_inside(options.out, options.work) || is_inside(options.work, options.out))
    throw UsageError(
        "--out and --work must be different folders, neither inside the other (--out " +
        escaped(options.out.string()) + ", --work " + escaped(options.work.string()) + ")");
}

// The tests of the tasks graded, or of all for --max-points (a student's check of task 1 may have
// built the programs of task 1 only: ./lab test task1), with their points.
std::vector<TestInfo> list_tests(const Options& options, const Kit& kit) {
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
  return tests;
}

// --max-points: each task's maximum, for the GitHub Classroom workflow of a release (./lab points).
int print_max_points(const Options& options, const std::vector<TestInfo>& tests) {
  std::map<int, double> max;
  for (const TestInfo& t : tests)
    if (!t.hidden || !options.student) max[t.task] += t.points;
  for (const auto& [task, points] : max)
    std::cout << "task" << task << ' ' << points << '\n';
  return 0;
}

void warn_of_empty(const std::vector<Submission>& submissions) {
  for (const Submission& s : submissions)
    if (s.fault.empty() && s.empty())
      std::cerr << "springlab-grade: " << escaped(s.name) << ": not one of the tasks' files "
                << "found (graded as the starter code): is " << escaped(s.folder.string())
                << " a submission?\n";
}

Settings settings_of(const Options& options) {
  Settings settings = options.settings;
  settings.tasks = options.tasks;
  settings.work = options.work;
  settings.hidden = !options.student;  // a student's check never shows the hidden tests
  return settings;
}

// The submissions to grade now, with their signatures, and those kept: grading named submissions
// into a folder of an earlier run, theirs are replaced, everyone else's kept; those graded before
// on the same files, kit and settings are kept as they are (a run stopped half way, started again,
// grades only the rest).
struct Plan {
  std::vector<Submission> to_grade;
  std::map<std::string, std::string> signature_by_name;  // of those to grade
  std::vector<std::string> kept;
};

Plan plan_grading(const Options& options, const Kit& kit, const std::vector<TestInfo>& tests,
                  const Settings& settings, const std::vector<Submission>& submissions,
                  const ResultsFolder& out) {
  const std::string run = run_signature(kit, tests, settings);
  Plan plan;
  for (const Submission& s : submissions) {
    const std::string signature = signature_of(run, s, settings);
    if (!options.student && out.unchanged(s.name, signature)) {
      plan.kept.push_back(s.name);
      continue;
    }
    plan.to_grade.push_back(s);
    plan.signature_by_name[s.name] = signature;
  }
  return plan;
}

// The results of other submissions in the folder, and those kept, in a line each.
void say_kept(const Options& options, const std::vector<Submission>& submissions, const Plan& plan,
              const ResultsFolder& out) {
  std::size_t others = 0;
  for (const auto& record : out.recorded()) {
    const auto& name = record.first;  // a named copy: Clang 14 cannot capture a structured binding
    others += std::none_of(submissions.begin(), submissions.end(),
                           [&](const Submission& s) { return s.name == name; });
  }
  if (!options.student && others > 0)
    std::cerr << "springlab-grade: " << escaped(options.out.string()) << " holds " << others
              << " other submission" << (others == 1 ? "'s" : "s'") << " results of earlier "
              << "runs: kept, and in the gradebook (--replace empties the folder first)\n";
  const std::vector<std::string>& kept = plan.kept;
  if (!kept.empty())
    std::cerr << "springlab-grade: " << kept.size() << " submission"
              << (kept.size() == 1 ? " was" : "s were")
              << " graded before with the same files, kit and settings: kept as they are ("
              << escaped(kept.front()) << (kept.size() > 1 ? ", ..." : "") << ")\n";
}

// What is about to run, in a line.
void say_grading(const Options& options, const std::vector<TestInfo>& tests,
                 const Settings& settings, const Grader& grader, std::size_t to_grade) {
  if (options.student) {
    std::cerr << "springlab-grade: compiling your code, then running each test in a process of "
              << "its own, plainly and with the sanitizers (which check every memory access)\n";
  } else if (to_grade > 0) {
    const auto hidden = std::count_if(tests.begin(), tests.end(), [&](const TestInfo& t) {
      return t.hidden && std::count(options.tasks.begin(), options.tasks.end(), t.task) > 0;
    });
    std::cerr << "springlab-grade: grading " << to_grade << " submission"
              << (to_grade == 1 ? "" : "s") << " (" << settings.jobs
              << " processes at once; a test may take " << grader.time_limit_text() << ")";
    if (hidden > 0)
      std::cerr << ", hidden tests included (" << hidden << ", shown to students after the due "
                << "date)";
    std::cerr << "\n";
  }
}

// Student mode: each task's feedback printed as soon as it and the tasks before it are done.
struct TasksInOrder {
  const Options& options;
  const Kit& kit;
  std::map<std::string, std::set<int>> tasks_done;

  void operator()(const SubmissionResult& r, int task) {
    if (!options.student) return;
    std::set<int>& done = tasks_done[r.submission.name];
    done.insert(task);
    for (const int t : options.tasks) {
      if (done.count(t) == 0) break;
      if (done.count(-t) > 0) continue;  // printed already
      std::cout << task_feedback(r, t, kit) << std::flush;
      done.insert(-t);
    }
  }
};

// Each submission as it is done: its results written, and its feedback (one submission, or a
// student's check) or a line of progress on the terminal.
struct SubmissionsDone {
  const Options& options;
  const Kit& kit;
  ResultsFolder& out;
  Plan plan;
  bool all_passed = true;
  std::size_t finished = 0;
  std::vector<std::string> not_graded{};  // "name: why"
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  void operator()(const SubmissionResult& r) {
    // Its own tests' time, not the batch's: in a batch the submissions share the machine.
    double seconds = 0.0;
    for (const auto& [task, result] : r.tasks)
      for (const TestResult& t : result.tests)
        seconds += t.seconds + t.sanitized_seconds;
    std::string fault = r.fault();
    try {
      out.write(r, plan.signature_by_name[r.submission.name], kit, seconds);
    } catch (const std::runtime_error& error) {
      if (fault.empty()) fault = error.what();
    }
    if (!fault.empty()) not_graded.push_back(escaped(r.submission.name) + ": " + fault);
    all_passed = all_passed && fault.empty() && r.points() == r.max_points();
    ++finished;
    if (options.student)
      std::cout << summary_feedback(r);
    else if (plan.to_grade.size() == 1)
      std::cout << feedback(r, kit);
    else
      print_progress(r, fault);
  }

  void print_progress(const SubmissionResult& r, const std::string& fault) const {
    const std::size_t total = plan.to_grade.size();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const long left = std::lround(elapsed / double(finished) * double(total - finished));
    std::cout << "[" << finished << "/" << total << "] " << escaped(r.submission.name) << ": "
              << (fault.empty()
                      ? points_text(r.points()) + " of " + points_text(r.max_points()) + " points"
                      : "not graded (" + fault + ")")
              << (finished < total ? " (about " + std::to_string(left) + " s left)" : "")
              << std::endl;
  }
};

// What was kept is shown as it was graded: one submission's feedback, or a line each.
void show_kept(const Options& options, std::size_t submissions,
               const std::vector<std::string>& kept, const ResultsFolder& out) {
  for (const std::string& name : kept) {
    const Recorded& r = out.recorded().at(name);
    if (submissions == 1) {
      std::ifstream saved(options.out / results_folder(name) / "feedback.txt");
      std::cout << saved.rdbuf();
      continue;
    }
    double points = 0.0, max = 0.0;
    for (const auto& [task, p] : r.points)
      points += p, max += r.max_points.at(task);
    std::cout << "[kept] " << escaped(name) << ": " << points_text(points) << " of "
              << points_text(max) << " points (graded before on the same files)" << std::endl;
  }
}

// Where the results are, what to review, and what could not be graded; the exit status.
int conclude(const Options& options, const ResultsFolder& out,
             const std::vector<std::string>& not_graded, bool all_passed) {
  if (!options.student) {
    std::cerr << "springlab-grade: " << escaped(options.out.string()) << "/gradebook.csv ("
              << out.recorded().size() << " submission" << (out.recorded().size() == 1 ? "" : "s")
              << "), and per submission feedback.txt, results.json and taskN.junit.xml\n";
    if (fs::exists(options.out / "review.csv"))
      std::cerr << "springlab-grade: some code calls what no task needs (ending the program, "
                << "files, threads, ...), or was not graded: " << escaped(options.out.string())
                << "/review.csv lists it\n";
  }
  if (!not_graded.empty()) {
    std::cerr << "springlab-grade: " << not_graded.size() << " submission"
              << (not_graded.size() == 1 ? " was" : "s were")
              << " not graded because of the grader itself, not of their code (run the same "
              << "command again once it is fixed: what was graded is kept):\n";
    for (const std::string& line : not_graded)
      std::cerr << "  " << line << "\n";
    return 3;
  }
  return options.student && !all_passed ? 1 : 0;
}

int grade(Options options) {
  if (options.calibrate && !options.submissions.empty())
    throw UsageError("--calibrate grades nothing: give no submission with it (" +
                     escaped(options.submissions.front()) + ")");
  const Kit kit = read_kit(options.kit);
  settle_folders(options, kit);
  const std::vector<TestInfo> tests = list_tests(options, kit);
  if (options.max_points) return print_max_points(options, tests);
  if (options.calibrate) return calibrate_only(options, kit, tests);
  if (options.submissions.empty()) throw UsageError("submission is required");
  const std::vector<Submission> submissions = find_all(options, kit);
  warn_of_empty(submissions);
  const Settings settings = settings_of(options);
  check_apart(options.out, submissions);
  check_apart(settings.work, submissions);
  ResultsFolder out(options.out, options.replace);
  const int work_lock = take_work_folder(settings.work);
  SubmissionsDone done{options, kit, out,
                       plan_grading(options, kit, tests, settings, submissions, out)};
  say_kept(options, submissions, done.plan, out);

  // Whether submission code can have namespaces of its own here: said once, on the terminal and
  // (when it cannot) in review.csv.
  const Isolation isolation = Isolation::probe({kit.root, options.out, settings.work});
  std::cerr << "springlab-grade: " << isolation.describe() << "\n";
  Grader grader(kit, tests, settings, isolation);
  grader.calibrate(options.kit.parent_path() / "calibration.txt", say_measuring);
  say_grading(options, tests, settings, grader, done.plan.to_grade.size());
  done.started = std::chrono::steady_clock::now();
  TasksInOrder task_done{options, kit, {}};
  show_kept(options, submissions.size(), done.plan.kept, out);
  grader.grade(
      done.plan.to_grade, [&](const SubmissionResult& r, int task) { task_done(r, task); },
      [&](const SubmissionResult& r) { done(r); });
  if (!options.student && !grader.phase_times().empty()) print_phase_times(grader.phase_times());
  try {
    out.write_gradebook(isolation.namespaces() ? "" : isolation.describe());
  } catch (const std::runtime_error& error) {
    done.not_graded.push_back(std::string("the gradebook: ") + error.what() +
                              " (each submission's own results are in its folder)");
  }
  close(work_lock);
  return conclude(options, out, done.not_graded, done.all_passed);
}

// The command line's options, in the order --help lists them.
void add_options(CLI::App& app, Options& options) {
  app.add_option("submission", options.submissions,
                 "a copy of tasks/, a student repository (its tasks/ is used) or a folder of "
                 "the loose .cpp files");
  app.add_option("--out", options.out,
                 "results: gradebook.csv and a folder per submission; the results of submissions "
                 "not graded now are kept")
      ->capture_default_str();
  CLI::Option* replace =
      app.add_flag("--replace", options.replace,
                   "empty --out first (else the other submissions' results there are kept)");
  app.add_option("--work", options.work,
                 "private copies and builds (default: the kit's build/grade/work/)");
  app.add_flag("--keep-work", options.settings.keep_work,
               "keep the copies, objects and libraries (removed as each is done, by default)");
  app.add_option("--jobs", options.settings.jobs,
                 "processes at once (default: the processors this machine or container allows)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--points", options.points, "the points file (default: the kit's)");
  app.add_option("--tasks", options.tasks, "the tasks to grade, as 1,2,5")
      ->delimiter(',')
      ->allow_extra_args(false)
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
  CLI::Option* student = app.add_flag(
      "--student", options.student,
      "a student's check: the feedback on the terminal; exit 1 unless every test passes");
  app.add_flag("--raw", options.settings.raw,
               "for instructors: show each failure's test file, line and expression as Catch2 "
               "states them, after the student's wording");
  CLI::Option* first_failure =
      app.add_flag("--first-failure", options.settings.first_failure,
                   "run each task's tests in order, plainly, and stop at its first failure (for "
                   "measuring feedback, not for grading)");
  CLI::Option* max_points =
      app.add_flag("--max-points", options.max_points,
                   "print each task's maximum (the sum of its tests' points) and grade nothing");
  app.add_flag("--calibrate", options.calibrate,
               "measure the reference's time per test of --tasks, unless this build already has "
               "(a student release ships them), and grade nothing (else the first grading "
               "measures it)")
      ->excludes(replace)
      ->excludes(student)
      ->excludes(first_failure)
      ->excludes(max_points);
  app.add_option("--kit", options.kit, "the kit.toml of the build to use")->capture_default_str();
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
  add_options(app, options);
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
  // Ctrl-C, a terminal closed, kill: every test process is killed before the grader ends (and
  // with it, should it be killed outright: each has the grader's death as its own).
  struct sigaction stop = {};
  stop.sa_handler = stop_on_signal;
  for (const int signal : {SIGINT, SIGTERM, SIGHUP})
    sigaction(signal, &stop, nullptr);
  try {
    return grade(options);
  } catch (const Interrupted& stopped) {
    std::cerr << "springlab-grade: stopped by " << strsignal(stopped.signal())
              << ": every test process it had started is ended; what was graded is kept in "
              << escaped(absolute_folder(options.out).string())
              << " (run the same command again to grade the rest)\n";
    return 128 + stopped.signal();
  } catch (const UsageError& error) {
    std::cerr << "springlab-grade: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "springlab-grade: " << error.what() << '\n';
    return 1;
  }
}
