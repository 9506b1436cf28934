#include "grading.hpp"

#include "checks.hpp"
#include "policy.hpp"
#include "reports.hpp"
#include "verdict.hpp"
#include "words.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

namespace springlab::grader {
namespace {

// The compiler and linker on submission code: generous (a task's file compiles in 1-5 s), but a
// template bomb ends, and no object, library or preprocessed file may grow past 32 MB (the
// kit's largest, a sanitized task 5 with debug information, is about 2 MB).
constexpr long largest_output_mb = 32;
constexpr long build_scratch_mb = 256;  // the compiler's /tmp

Limits build_limits() {
  Limits limits;
  limits.wall_seconds = 60;
  limits.cpu_seconds = 60;
  limits.address_space_mb = 4096;
  limits.file_size_mb = largest_output_mb;
  return limits;
}

// The compiler's messages, without the lines that only repeat where the kit compiled them.
std::string first_lines(const std::string& text, std::size_t count) {
  std::istringstream lines(text);
  std::string line, result;
  std::size_t kept = 0;
  while (std::getline(lines, line) && kept < count) {
    result += line + '\n';
    ++kept;
  }
  if (std::getline(lines, line)) result += "...\n";
  return result;
}

// Paths in the compiler's messages as the student knows them: tasks/task1_.../file.cpp and
// common/include/..., not where the grader keeps its copy or where the kit lies.
std::string student_paths(std::string text, const fs::path& copy, const fs::path& kit) {
  const fs::path work = copy.parent_path().parent_path().parent_path().parent_path();
  for (const std::string& prefix : {copy.parent_path().parent_path().string() + "/",
                                    work.string() + "/builds/", kit.string() + "/"})
    for (auto at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at))
      text.erase(at, prefix.size());
  return text;
}

// The compiler's messages with the functions named as the student wrote them: the grader
// compiles a submission's tasks in a namespace of their own (springlab::submission), which
// the student's file never names.
std::string as_written(std::string text) {
  const std::string inner = "springlab::submission::";
  for (auto at = text.find(inner); at != std::string::npos; at = text.find(inner, at))
    text.erase(at + 11, 12);  // "springlab::" stays
  return text;
}

std::string stop_text(Stop stop, const std::string& output) {
  if (output.find("File size limit exceeded") != std::string::npos)
    return "(the compiler was stopped: its output grew past " + std::to_string(largest_output_mb) +
           " MB)\n";
  switch (stop) {
    case Stop::wall_time:
    case Stop::cpu_time:
      return "(the compiler was stopped: it ran too long)\n";
    case Stop::memory:
      return "(the compiler was stopped: it used too much memory)\n";
    case Stop::output:
      return "(the compiler was stopped: it printed too much)\n";
    case Stop::none:
      break;
  }
  return "";
}

// What task N's times depend on: its programs, its library parts and its tests' names.
std::string task_signature(const Kit& kit, const std::vector<TestInfo>& tests, int task) {
  std::ostringstream s;
  const auto stamp = [&](const fs::path& path) {
    std::error_code error;
    s << path.string() << ' ' << fs::file_size(path, error) << ' '
      << fs::last_write_time(path, error).time_since_epoch().count() << '\n';
  };
  stamp(kit.programs.at(task));
  stamp(kit.sanitized_programs.at(task));
  for (const fs::path& part : kit.library_parts.at(task))
    stamp(part);
  for (const TestInfo& test : tests)
    if (test.task == task) s << test.name << '\n';
  std::ostringstream hex;
  hex << std::hex << std::hash<std::string>{}(s.str());
  return hex.str();
}

// Why the work folder cannot take more ("" when it can): less than 16 MB or 64 files free.
std::string work_folder_full(const fs::path& work) {
  struct statvfs space = {};
  if (::statvfs(work.c_str(), &space) != 0) return "";
  const double free_mb = double(space.f_bavail) * double(space.f_frsize) / double(1 << 20);
  if (free_mb >= 16.0 && space.f_favail >= 64) return "";
  std::ostringstream why;
  why << "the grader's work folder " << escaped(work.string()) << " is full ("
      << std::lround(free_mb) << " MB, " << space.f_favail << " files free)";
  return why.str();
}

// A calibration cache as read: each task's signature, its tests' times, and the tasks holding a
// time of 0 (a test never run: a cache written under --first-failure before issue 27's fix).
struct CacheContents {
  std::map<int, std::string> signatures;
  Calibration times;
  std::set<int> unmeasured;
};

CacheContents read_cache(const fs::path& file) {
  CacheContents cache;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line) && line != "---") {
    std::istringstream words(line);
    std::string word, signature;
    int task = 0;
    if (words >> word >> task >> signature && word == "task") cache.signatures[task] = signature;
  }
  std::string variant, name;
  double seconds = 0;
  int task = 0;
  while (in >> variant >> seconds >> task && std::getline(in, name)) {
    if (cache.signatures.count(task) > 0) cache.times[variant][name.substr(1)] = {task, seconds};
    if (seconds <= 0) cache.unmeasured.insert(task);
  }
  return cache;
}

// Drops every time of `task` from `times`.
void forget_task(Calibration& times, int task) {
  for (auto& [variant, tests] : times)
    std::erase_if(tests, [task](const auto& entry) { return entry.second.task == task; });
}

// The times `read` holds into `times`, and the signatures of the tasks whose lines are kept: a
// task with a time of 0 is measured again (unless the times were shipped, never measured here).
std::map<int, std::string> take_cached(const CacheContents& read, bool shipped,
                                       Calibration& times) {
  std::map<int, std::string> signatures = read.signatures;
  for (const auto& [variant, tests] : read.times)
    for (const auto& [name, time] : tests)
      times[variant][name] = time;
  if (!shipped)
    for (const int t : read.unmeasured)
      signatures.erase(t);
  return signatures;
}

// The tasks graded whose programs changed since their times were measured, or never were: their
// times forgotten, their new signatures in `signatures`.
std::vector<int> tasks_to_measure(const Kit& kit, const std::vector<TestInfo>& tests,
                                  const std::vector<int>& tasks,
                                  std::map<int, std::string>& signatures, Calibration& times) {
  std::vector<int> missing;
  for (const int task : tasks) {
    const std::string signature = task_signature(kit, tests, task);
    if (signatures.count(task) > 0 && signatures[task] == signature) continue;
    forget_task(times, task);
    signatures[task] = signature;
    missing.push_back(task);
  }
  return missing;
}

// The reference's times per test from its grading into `times`; throws when it failed a test.
void take_measured(const SubmissionResult& reference, Calibration& times) {
  if (const std::string fault = reference.fault(); !fault.empty())
    throw std::runtime_error("the reference's times could not be measured: " + fault);
  std::string failures;
  for (const auto& [task, result] : reference.tasks)
    for (const TestResult& t : result.tests)
      if (!t.passed)
        failures += "\n  task " + std::to_string(task) + ": " + t.test->name + ": " +
                    (result.problem.empty() ? t.message : result.problem);
      else {
        times["plain"][t.test->name] = {task, t.seconds};
        times["sanitized"][t.test->name] = {task, t.sanitized_seconds};
      }
  if (!failures.empty())
    throw std::runtime_error(
        "the kit's own solutions fail tests, so nothing can be graded "
        "fairly (rebuild the kit; if it persists, the kit is broken):" +
        failures);
}

// Another grading may have written the cache since it was read (two started side by side, each
// measuring its own tasks): the tasks `now` holds that this one does not grade (`graded`) are
// taken as they are now, so that neither drops the other's; the tasks this one grades keep the
// times of its own programs. (Only the moment between this reading and the rename of the cache
// is left for another grading to slip into.)
void take_others(const CacheContents& now, const std::vector<int>& graded,
                 std::map<int, std::string>& signatures, Calibration& times) {
  for (const auto& [task, signature] : now.signatures) {
    if (std::ranges::find(graded, task) != graded.end() || now.unmeasured.count(task) > 0) continue;
    signatures[task] = signature;
    forget_task(times, task);
    for (const auto& [variant, tests] : now.times)
      for (const auto& [name, time] : tests)
        if (time.task == task) times[variant][name] = time;
  }
}

// Writes the cache whole, then renames it: another grader reading it meanwhile sees the old or the
// new. A cache that cannot be written costs only the measurement again next time (said to
// `progress`; false).
bool write_cache(const fs::path& cache, const std::map<int, std::string>& signatures,
                 const Calibration& times,
                 const std::function<void(const std::string&)>& progress) {
  std::ostringstream out;
  for (const auto& [task, signature] : signatures)
    out << "task " << task << ' ' << signature << '\n';
  out << "---\n";
  for (const auto& [name, variant] : times)
    for (const auto& [test, time] : variant)
      out << name << ' ' << time.seconds << ' ' << time.task << ' ' << test << '\n';
  try {
    write_file(cache, out.str());
  } catch (const std::runtime_error& error) {
    if (progress) progress(std::string(error.what()) + " (measured again next time)");
    return false;
  }
  return true;
}

}  // namespace

double SubmissionResult::points() const {
  double sum = 0.0;
  for (const auto& [n, task] : tasks)
    sum += task.points();
  return sum;
}

std::string SubmissionResult::fault() const {
  for (const auto& [n, task] : tasks)
    if (!task.fault.empty()) return "task " + std::to_string(n) + ": " + task.fault;
  return "";
}

double SubmissionResult::max_points() const {
  double sum = 0.0;
  for (const auto& [n, task] : tasks)
    sum += task.max_points();
  return sum;
}

// One task's files as one or more submissions hold them, from copy to verdicts.
struct Grader::TaskBuild {
  int task = 0;
  fs::path copy;                     // the private copy of the task's files
  fs::path folder;                   // its objects and libraries
  std::vector<std::string> sources;  // the kit's files of the task, compiled
  std::string problem;               // why the copy cannot be graded at all (a file too large)
  TaskResult result;
  std::vector<int> passed_plain;  // tests waiting for the sanitized library
  bool sanitized_started = false, sanitized_ready = false;
  std::string sanitized_problem;  // set when the sanitized build failed
  std::string sanitized_fault;    // set when it failed because of the grader
  int tests_open = 0;
  std::vector<std::function<void()>> on_finish;

  fs::path object(const std::string& source, const Variant& v) const {
    return folder / (v.name + "-" + fs::path(source).stem().string() + ".o");
  }
  fs::path library(const Variant& v) const { return folder / (v.name + ".so"); }
  void finish() {
    for (auto& f : on_finish)
      f();
    on_finish.clear();
  }
};

Grader::Grader(const Kit& kit, const std::vector<TestInfo>& tests, Settings settings,
               const Isolation& isolation)
    : kit_(kit), tests_(tests), settings_(std::move(settings)), isolation_(isolation) {}

std::string Grader::time_limit_text() const {
  std::ostringstream text;
  text << settings_.time_factor << " times the reference's time, at least " << settings_.time_floor
       << " s";
  return text.str();
}

Limits Grader::test_limits(const TestInfo& test, const Variant& variant) const {
  Limits limits;
  double reference = settings_.time_floor;
  if (const auto v = calibration_.find(variant.name); v != calibration_.end())
    if (const auto t = v->second.find(test.name); t != v->second.end())
      reference = t->second.seconds;
  limits.wall_seconds = std::max(settings_.time_floor, settings_.time_factor * reference);
  limits.cpu_seconds = limits.wall_seconds;
  // The sanitizers reserve terabytes of address space: their memory is watched instead.
  const bool sanitized = &variant == &kit_.sanitized;
  limits.address_space_mb = sanitized ? 0 : settings_.memory_mb;
  limits.resident_mb = sanitized ? settings_.memory_mb : 0;
  limits.file_size_mb = 0;
  limits.output_kept = settings_.output_kept;
  limits.output_limit = settings_.output_limit;
  return limits;
}

// The stages of a task build, each started by the end of the one before: compile plain, check
// what the code includes and names, link; then every test plain, while the sanitized library is
// built; then, for each test that passed, the same test sanitized.
class Grader::Pipeline {
 public:
  Pipeline(const Grader& grader, ProcessPool& pool, bool generous)
      : g_(grader), kit_(grader.kit_), pool_(pool), generous_(generous) {
    run_folder_ = g_.settings_.work / "run";
    fs::create_directories(run_folder_);
    fs::create_directories(g_.settings_.work / "tmp");
    g_.isolation_.give_to_sandbox(g_.settings_.work / "tmp");
    stand_ins_ = prepare_stand_ins(kit_, g_.settings_.work / "stand-ins");
    limits_text_.time = generous ? "60 s while measuring the reference" : g_.time_limit_text();
  }

  void start(const std::shared_ptr<TaskBuild>& b) {
    for (const TestInfo* test : tests_of_task(g_.tests_, b->task, g_.settings_.hidden)) {
      TestResult result;
      result.test = test;
      b->result.tests.push_back(result);
    }
    b->tests_open = int(b->result.tests.size());
    if (!b->problem.empty()) return fail_all(b, "not graded: " + b->problem);
    fs::create_directories(b->folder);
    g_.isolation_.give_to_sandbox(b->folder);
    // The source policy first, on the files as written and then as the preprocessor sees them:
    // nothing the policy forbids ever reaches the compiler proper.
    if (const auto breach = check_sources(b->copy, b->sources))
      return fail_all(b, "not graded: " + breach->text());
    preprocess(b, 0, {b->sources.begin(), b->sources.end()});
  }

 private:
  // ok, the linker's messages, and the grader's own fault ("" when none).
  using Then = std::function<void(bool ok, const std::string& messages, const std::string& fault)>;

  // Runs c in the pool, its time counted under `phase` (Grader::phase_times) unless measuring
  // the reference.
  void add(std::string phase, Command c, std::function<void(Outcome)> done) {
    pool_.add(std::move(c), [this, phase = std::move(phase), done = std::move(done)](Outcome o) {
      if (!generous_) {
        PhaseTime& t = g_.phase_times_[phase];
        ++t.count;
        t.wall_seconds += o.wall_seconds;
      }
      done(std::move(o));
    });
  }
  static std::string of(const std::string& phase, bool sanitized) {
    return sanitized ? phase + " (sanitized)" : phase;
  }
  // ok, the compiler's messages, what the code may not include and the grader's own fault ("" when
  // nothing).
  using Compiled =
      std::function<void(bool, const std::string&, const std::string&, const std::string&)>;

  // What compiling one file gave, kept for any later copy whose own files that the compiler read
  // are the same, byte for byte: a mutant, or a student's untouched file, is compiled once.
  struct Object {
    fs::path path;
    fs::path copy;                  // the copy it was compiled from
    std::vector<std::string> read;  // the copy's files the compiler read
    bool ok = false;
    std::string messages, problem;
    std::string fault;  // the grader's own: never kept for another copy
  };
  // By run, file, its digest and the copy's file names.
  std::map<std::string, std::vector<Object>> objects_;
  // Compilations under way, by the same key: what waits for each to end, to look again.
  std::map<std::string, std::vector<std::function<void()>>> compiling_;
  const Grader& g_;
  const Kit& kit_;
  ProcessPool& pool_;
  bool generous_;
  fs::path run_folder_;
  LimitsText limits_text_;
  StandIns stand_ins_;  // what the policy's own reading of the copies includes

  // The compiler's and the linker's temporary files go to the sandbox's scratch (or, without
  // namespaces, to the work folder), never elsewhere.
  std::vector<std::string> build_environment() const {
    std::vector<std::string> env = plain_environment();
    env.push_back(
        "TMPDIR=" +
        (g_.isolation_.namespaces() ? fs::path("/tmp") : g_.settings_.work / "tmp").string());
    return env;
  }

  // What a compiler, linker or nm run on a task build may see: its copy (read-only), its own
  // folder (its outputs), and the kit's headers, precompiled headers and library parts.
  View build_view(const TaskBuild& b) const {
    View view;
    view.bindings = {{b.copy, {}, false},
                     {b.folder, {}, true},
                     {kit_.headers, {}, false},
                     {kit_.pch, {}, false},
                     {stand_ins_.folder.parent_path(), {}, false}};
    if (!kit_.linker_script.empty()) view.bindings.push_back({kit_.linker_script, {}, false});
    for (const fs::path& part : kit_.library_parts.at(b.task))
      view.bindings.push_back({part, {}, false});
    view.scratch_mb = build_scratch_mb;
    view.directory = b.folder;
    return view;
  }

  Command build_command(const TaskBuild& b, std::vector<std::string> argv,
                        const fs::path& directory) const {
    Command c;
    c.argv = std::move(argv);
    c.env = build_environment();
    c.directory = directory.string();
    c.limits = build_limits();
    View view = build_view(b);
    view.directory = directory;
    g_.isolation_.confine(c, view);
    if (!g_.isolation_.namespaces()) c.directory = directory.string();
    return c;
  }

  // Preprocesses the task's files one at a time, each twice in the sandbox: against the policy's
  // stand-ins (policy.hpp, StandIns: every line of the output is the copy's, and all of it is
  // checked), then as the build does (`-E`: what the library's macros made of the copy's lines,
  // and which files they included); then compiles.
  void preprocess(const std::shared_ptr<TaskBuild>& b, std::size_t index,
                  std::vector<std::string> unchecked) {
    if (index == b->sources.size()) return compile_checked(b);
    const std::string& source = b->sources[index];
    const fs::path output = b->folder / (fs::path(source).stem().string() + ".own.ii");
    std::vector<std::string> argv = stand_in_flags(kit_.plain.compile, stand_ins_);
    for (const std::string& arg :
         {std::string("-include"), stand_ins_.macros.string(), std::string("-E"),
          (b->copy / source).string(), std::string("-o"), output.string()})
      argv.push_back(arg);
    Command c = build_command(*b, std::move(argv), b->folder);
    add("preprocess (policy)", std::move(c),
        [this, b, index, output, unchecked](Outcome o) mutable {
          if (!preprocessed(b, o)) return;
          std::ifstream in(output);
          const Preprocessed p = check_stand_in_output(in, b->copy, stand_ins_);
          if (p.breach) return fail_all(b, "not graded: " + p.breach->text());
          if (!check_included(b, p.own_files, unchecked)) return;
          std::error_code error;
          fs::remove(output, error);
          preprocess_as_built(b, index, std::move(unchecked));
        });
  }

  // False, the task failed, when a preprocessing did not succeed: a file that does not
  // preprocess does not compile either (and what was not checked is never compiled), as the
  // preprocessor's messages say.
  bool preprocessed(const std::shared_ptr<TaskBuild>& b, const Outcome& o) {
    if (o.exited && o.exit_code == 0) return true;
    if (const std::string fault = fault_of(o, "the preprocessor"); !fault.empty()) {
      fault_all(b, fault);
      return false;
    }
    std::string messages = stop_text(o.stopped, o.output) + o.start_error +
                           student_paths(o.output, b->copy, kit_.root);
    if (quotes_foreign_file(o.output, b->copy))
      messages =
          "(the compiler's messages are not shown: they quote a file that is not "
          "your submission's)\n";
    fail_all(b, "does not compile:\n" + first_lines(messages, 60));
    return false;
  }

  // Checks the copy's files in `included` that `unchecked` does not list yet as written (and
  // lists them); false, the task failed, when one breaks the policy.
  bool check_included(const std::shared_ptr<TaskBuild>& b, const std::vector<std::string>& included,
                      std::vector<std::string>& unchecked) {
    std::vector<std::string> fresh;
    for (const std::string& file : included)
      if (std::find(unchecked.begin(), unchecked.end(), file) == unchecked.end()) {
        unchecked.push_back(file);
        fresh.push_back(file);
      }
    if (const auto breach = check_sources(b->copy, fresh)) {
      fail_all(b, "not graded: " + breach->text());
      return false;
    }
    return true;
  }

  void preprocess_as_built(const std::shared_ptr<TaskBuild>& b, std::size_t index,
                           std::vector<std::string> unchecked) {
    const std::string& source = b->sources[index];
    const fs::path output = b->folder / (fs::path(source).stem().string() + ".ii");
    std::vector<std::string> argv = kit_.plain.compile;
    for (const std::string& arg : {std::string("-E"), std::string("-fpch-preprocess"),
                                   (b->copy / source).string(), std::string("-o"), output.string()})
      argv.push_back(arg);
    Command c = build_command(*b, std::move(argv), b->folder);
    add("preprocess", std::move(c), [this, b, index, output, unchecked](Outcome o) mutable {
      if (!preprocessed(b, o)) return;
      std::ifstream in(output);
      const Preprocessed p = check_preprocessed(in, include_roots(*b));
      if (p.breach) return fail_all(b, "not graded: " + p.breach->text());
      if (!check_included(b, p.own_files, unchecked)) return;
      std::error_code error;
      fs::remove(output, error);
      preprocess(b, index + 1, std::move(unchecked));
    });
  }

  IncludeRoots include_roots(const TaskBuild& b) const {
    IncludeRoots roots;
    roots.copy = b.copy;
    roots.kit_headers = kit_.headers;
    roots.standard = kit_.system_headers;
    const std::vector<std::string>& flags = kit_.plain.compile;
    for (std::size_t i = 0; i + 1 < flags.size(); ++i)
      if (flags[i] == "-isystem") roots.eigen.emplace_back(flags[i + 1]);
    return roots;
  }

  void compile_checked(const std::shared_ptr<TaskBuild>& b) {
    compile(b, kit_.plain,
            [this, b](bool ok, const std::string& messages, const std::string& problem,
                      const std::string& fault) {
              if (!fault.empty()) return fault_all(b, fault);
              // A file it may not include is refused whether the code compiles or not.
              if (!problem.empty()) return fail_all(b, "not graded: " + problem);
              if (!ok) return fail_all(b, "does not compile:\n" + messages);
              b->result.warnings = messages;
              check(b);
            });
  }

  void compile(const std::shared_ptr<TaskBuild>& b, const Variant& v, Compiled then) {
    struct Stage {
      std::size_t open = 0;
      bool ok = true;
      std::string messages, problem, fault;
    };
    auto stage = std::make_shared<Stage>();
    stage->open = b->sources.size();
    for (const std::string& source : b->sources)
      compile_one(b, v, source, [stage, then](const Object& o) {
        stage->ok = stage->ok && o.ok;
        stage->messages += o.messages;
        if (stage->problem.empty()) stage->problem = o.problem;
        if (stage->fault.empty()) stage->fault = o.fault;
        if (--stage->open == 0)
          then(stage->ok, first_lines(stage->messages, 60), stage->problem, stage->fault);
      });
  }

  void compile_one(const std::shared_ptr<TaskBuild>& b, const Variant& v, const std::string& source,
                   std::function<void(const Object&)> done) {
    std::string key = v.name + '\0' + source + '\0' + file_digest(b->copy / source);
    for (const fs::directory_entry& file : fs::directory_iterator(b->copy))
      key += '\0' + file.path().filename().string();  // what an #if __has_include could see
    const fs::path path = b->object(source, v);
    for (const Object& o : objects_[key])
      if (std::all_of(o.read.begin(), o.read.end(), [&](const std::string& file) {
            return same_file(o.copy / file, b->copy / file);
          })) {
        // The object may be gone with its build's folder (removed once graded): then compile.
        std::error_code error;
        if (o.ok) fs::copy_file(o.path, path, fs::copy_options::overwrite_existing, error);
        if (!error) return done(o);
      }
    if (const auto it = compiling_.find(key); it != compiling_.end()) {
      it->second.push_back([=, this] { compile_one(b, v, source, done); });
      return;
    }
    compiling_[key];
    std::vector<std::string> argv = v.compile;
    // Paths in the object (debug information, __FILE__) as tasks/..., wherever the copy is: an
    // object made for one submission may serve another, and must not name the first.
    const fs::path top = b->copy.parent_path().parent_path();
    for (const std::string& arg : {"-ffile-prefix-map=" + top.string() + "=.", std::string("-MD"),
                                   std::string("-MF"), path.string() + ".d", std::string("-c"),
                                   (b->copy / source).string(), std::string("-o"), path.string()})
      argv.push_back(arg);
    // In the folder above the copy, so that the objects name their files ./tasks/... (see above).
    Command c = build_command(*b, std::move(argv), top);
    add(of("compile", &v == &kit_.sanitized), std::move(c),
        [this, b, &v, source, key, path, done](Outcome outcome) {
          Object o;
          o.path = path;
          o.copy = b->copy;
          o.ok = outcome.exited && outcome.exit_code == 0;
          o.messages = stop_text(outcome.stopped, outcome.output) +
                       as_written(student_paths(outcome.output, b->copy, kit_.root));
          if (!outcome.start_error.empty()) o.messages += outcome.start_error + "\n";
          if (!o.ok) o.fault = fault_of(outcome, "the compiler");
          const fs::path copy = fs::weakly_canonical(b->copy);
          for (const fs::path& file : read_dependencies(path.string() + ".d")) {
            const fs::path inside = fs::weakly_canonical(file).lexically_relative(copy);
            if (!inside.empty() && *inside.begin() != "..") o.read.push_back(inside.string());
            const std::string problem = include_problem(file, b->copy, kit_.pch, kit_);
            if (o.problem.empty() && !problem.empty()) o.problem = source + ": " + problem;
          }
          // Never the compiler's words about a file the submission may not read: they quote it.
          if (quotes_foreign_file(outcome.output, b->copy))
            o.messages =
                "(the compiler's messages are not shown: they quote a file that is not "
                "your submission's)\n";
          if (o.fault.empty()) objects_[key].push_back(o);
          const std::vector<std::function<void()>> waiting = std::move(compiling_[key]);
          compiling_.erase(key);
          done(o);
          for (const auto& again : waiting)
            again();
        });
  }

  // True when the compiler's messages name a file outside the copy, the kit's headers and the
  // system's (a message quotes the line it is about).
  bool quotes_foreign_file(const std::string& messages, const fs::path& copy) const {
    std::istringstream lines(messages);
    std::string line;
    while (std::getline(lines, line))
      for (auto at = line.find('/'); at != std::string::npos; at = line.find('/', at + 1)) {
        if (at > 0 && line[at - 1] != ' ') continue;  // a path starts a word
        const std::string path = line.substr(at, line.find_first_of(": ", at) - at);
        if (!include_problem(path, copy, kit_.pch, kit_).empty()) return true;
      }
    return false;
  }

  // What the objects name (from nm); then the library.
  void check(const std::shared_ptr<TaskBuild>& b) {
    std::vector<std::string> argv = {kit_.nm.string(), "-P", "-A"};
    for (const std::string& source : b->sources)
      argv.push_back(b->object(source, kit_.plain).string());
    Command c = build_command(*b, std::move(argv), b->folder);
    c.limits.output_kept = c.limits.output_limit;
    add("nm", std::move(c), [this, b](Outcome o) {
      if (!o.exited || o.exit_code != 0) {
        const std::string fault = fault_of(o, "nm");
        return fault_all(b, fault.empty() ? "nm could not read the objects: " +
                                                first_lines(printable(o.output), 3)
                                          : fault);
      }
      b->result.review = review_notes(o.output);
      const std::vector<std::string> problems = symbol_problems(o.output);
      if (!problems.empty()) {
        std::string text = "not graded:";
        for (const std::string& p : problems)
          text += "\n" + p;
        return fail_all(b, text);
      }
      link(b, kit_.plain,
           [this, b](bool ok, const std::string& messages, const std::string& fault) {
             if (!fault.empty()) return fault_all(b, fault);
             if (!ok) return fail_all(b, "does not link:\n" + messages);
             if (g_.settings_.first_failure) return run_plain(b, 0);
             for (int i = 0; i < int(b->result.tests.size()); ++i)
               run_plain(b, i);
           });
    });
  }

  void link(const std::shared_ptr<TaskBuild>& b, const Variant& v, Then then) {
    std::vector<std::string> argv = v.link;
    argv.push_back("-o");
    argv.push_back(b->library(v).string());
    // The submission's objects first, so that their copies of inline functions are the ones kept.
    for (const std::string& source : b->sources)
      argv.push_back(b->object(source, v).string());
    for (const fs::path& part : kit_.library_parts.at(b->task))
      argv.push_back(part.string());
    Command c = build_command(*b, std::move(argv), b->folder);
    add(of("link", &v == &kit_.sanitized), std::move(c), [this, b, then](Outcome o) {
      const bool ok = o.exited && o.exit_code == 0;
      then(ok, first_lines(student_paths(o.output, b->copy, kit_.root), 30),
           ok ? "" : fault_of(o, "the linker"));
    });
  }

  void build_sanitized(const std::shared_ptr<TaskBuild>& b) {
    compile(b, kit_.sanitized,
            [this, b](bool ok, const std::string& messages, const std::string&,
                      const std::string& fault) {
              if (!fault.empty()) return sanitized_ready(b, "", fault);
              if (!ok) return sanitized_ready(b, "it does not compile:\n" + messages, "");
              link(b, kit_.sanitized,
                   [this, b](bool linked, const std::string& link_messages,
                             const std::string& link_fault) {
                     sanitized_ready(b, linked ? "" : "it does not link:\n" + link_messages,
                                     link_fault);
                   });
            });
  }

  void sanitized_ready(const std::shared_ptr<TaskBuild>& b, const std::string& problem,
                       const std::string& fault) {
    b->sanitized_problem = problem;
    b->sanitized_fault = fault;
    b->sanitized_ready = true;
    for (const int index : b->passed_plain)
      run_sanitized(b, index);
    b->passed_plain.clear();
  }

  // A test in the sandbox sees the harness, the worker and the library under the same names in
  // both runs (/grade/...), so that nothing in its view tells the plain run from the sanitized one
  // but the sanitizers' own run-time.
  Command test_command(const TestInfo& test, const Variant& v, const TaskBuild& b) const {
    Command c;
    const bool sanitized = &v == &kit_.sanitized;
    const fs::path harness = "/grade/harness", worker = "/grade/worker",
                   library = "/grade/library.so";
    c.argv = {harness.string(), "--run", test.name, worker.string(), library.string()};
    if (sanitized) {
      c.argv.push_back("--resident-mb");
      c.argv.push_back(std::to_string(g_.settings_.memory_mb));
    }
    c.env = plain_environment();
    c.env.insert(c.env.end(), v.env.begin(), v.env.end());
    c.directory = run_folder_.string();
    c.secret = new_secret();
    c.limits = g_.test_limits(test, v);
    if (generous_) c.limits.wall_seconds = c.limits.cpu_seconds = 60;
    // The harness names a task function that stops answering, before the grader's clock ends it:
    // in the plain run only, where an endless loop shows first; in the sanitized run its earlier
    // stop would cut short the time a memory hog has to reach the resident-memory limit.
    if (!sanitized) {
      c.argv.push_back("--wait-limit");
      c.argv.push_back(std::to_string(0.8 * c.limits.wall_seconds));
    }
    View view;
    view.bindings = {
        {kit_.programs.at(test.task), harness, false},
        {(sanitized ? kit_.sanitized_programs : kit_.programs).at(test.task), worker, false},
        {b.library(v), library, false}};
    view.scratch_mb = 16;
    view.test = true;  // the worker filters itself, and the harness signals it
    g_.isolation_.confine(c, view);
    return c;
  }

  void run_plain(const std::shared_ptr<TaskBuild>& b, int index) {
    Command c = test_command(*b->result.tests[std::size_t(index)].test, kit_.plain, *b);
    const std::string secret = c.secret;
    const Limits limits = c.limits;
    add("test", std::move(c), [this, b, index, secret, limits](Outcome o) {
      TestResult& t = b->result.tests[std::size_t(index)];
      if (const std::string fault = fault_of_test(o); !fault.empty()) {
        // In order, the tests after this one were never started: settled here, or the task
        // would never finish.
        if (g_.settings_.first_failure)
          stop_after(b, index, "not run: the grading stopped at the grader's own fault");
        return test_fault(b, t, fault);
      }
      const RunVerdict v = judge(o, secret, limits, limits_text_);
      t.passed = v.passed;
      t.message = g_.settings_.raw ? v.message : without_raw_lines(v.message);
      t.printed = o.output;
      t.printed_bytes = o.output_bytes;
      if (!g_.settings_.raw) without_assertion_lines(t);
      t.seconds = o.wall_seconds;
      // A crash, or a failed check (an index out of Eigen's range, say), is run again with the
      // sanitizers, which can say what corrupted memory first.
      const bool crashed = !t.passed && (t.message.rfind("crashed: ", 0) == 0 ||
                                         t.message.rfind("a check failed", 0) == 0);
      if (g_.settings_.first_failure) {
        // In order, plainly: the next test after a pass; after the first failure, none (its
        // crash still explained by the sanitizers).
        if (t.passed && index + 1 < int(b->result.tests.size())) {
          settle(b);
          return run_plain(b, index + 1);
        }
        if (!t.passed) stop_after(b, index, "not run: the grading stopped at the first failure");
        if (!crashed) return settle(b);
      }
      if (!t.passed && !crashed) return settle(b);
      if (b->sanitized_ready) return run_sanitized(b, index);
      // The sanitized library is built once a test has passed plainly (or crashed): code that
      // passes none needs none.
      if (b->passed_plain.empty() && !b->sanitized_started) {
        b->sanitized_started = true;
        build_sanitized(b);
      }
      b->passed_plain.push_back(index);
    });
  }

  void run_sanitized(const std::shared_ptr<TaskBuild>& b, int index) {
    TestResult& plain = b->result.tests[std::size_t(index)];
    const bool crashed = !plain.passed;  // plainly; it is here to be explained
    if (!b->sanitized_fault.empty()) return test_fault(b, plain, b->sanitized_fault);
    if (!b->sanitized_problem.empty()) {
      if (crashed) return settle(b);
      plain.passed = false;
      plain.message = "passes, but the build with the sanitizers failed: " + b->sanitized_problem;
      return settle(b);
    }
    Command c = test_command(*plain.test, kit_.sanitized, *b);
    const std::string secret = c.secret;
    const Limits limits = c.limits;
    add("test (sanitized)", std::move(c), [this, b, index, secret, limits, crashed](Outcome o) {
      TestResult& t = b->result.tests[std::size_t(index)];
      if (const std::string fault = fault_of_test(o); !fault.empty())
        return test_fault(b, t, fault);
      t.sanitized_seconds = o.wall_seconds;
      const RunVerdict v = judge(o, secret, limits, limits_text_);
      if (crashed) {
        // Explained only when the sanitizers name a memory error or undefined behaviour, or a
        // failed check where the plain run only crashed.
        const bool explained =
            v.message.rfind("memory error", 0) == 0 ||
            v.message.rfind("undefined behaviour", 0) == 0 ||
            (v.message.rfind("a check failed", 0) == 0 &&
             (t.message.rfind("crashed: ", 0) == 0 ||
              v.message.find(" (tasks/task") != std::string::npos));  // now with the line
        // A check that failed in both runs is said once, as the sanitized run names its line.
        const bool same_check =
            t.message.rfind("a check failed", 0) == 0 && v.message.rfind("a check failed", 0) == 0;
        if (!v.passed && explained) {
          t.message = (same_check ? ""
                                  : t.message.substr(0, t.message.find('\n')) +
                                        "; run again with the sanitizers, which check every "
                                        "memory access: ") +
                      (g_.settings_.raw ? v.message : without_raw_lines(v.message));
          t.printed = o.output;
          t.printed_bytes = o.output_bytes;
          if (!g_.settings_.raw) without_sanitizer_report(t), without_assertion_lines(t);
        }
        return settle(b);
      }
      if (!v.passed) {
        t.passed = false;
        t.message = "passes, but not with the sanitizers, which check every memory access: " +
                    (g_.settings_.raw ? v.message : without_raw_lines(v.message));
        t.printed = o.output;
        t.printed_bytes = o.output_bytes;
        if (!g_.settings_.raw) without_sanitizer_report(t);
      }
      settle(b);
    });
  }

  // The sanitizer's own report (its stack names the kit's tests and their lines) is for
  // instructors: the message has already said what it found and where in the student's code.
  static void without_sanitizer_report(TestResult& t) {
    // AddressSanitizer's report starts with a banner, UndefinedBehaviorSanitizer's with the line
    // "FILE:LINE:COLUMN: runtime error: ...".
    const std::string banner =
        "=================================================================\n==";
    auto at = std::min(t.printed.find(banner), t.printed.find(": runtime error: "));
    if (at == std::string::npos) return;
    if (t.printed.compare(at, 2, ": ") == 0) {
      const auto line = t.printed.rfind('\n', at);
      at = line == std::string::npos ? 0 : line + 1;
    }
    t.printed.resize(at);
    t.printed_bytes = std::min(t.printed_bytes, at);
  }

  // A failed assert()'s own line ("worker: /usr/include/eigen3/...: Assertion `...' failed.")
  // is for instructors: the message has already said what the check was, in a student's words.
  static void without_assertion_lines(TestResult& t) {
    const std::string kept = grader::without_assertion_lines(t.printed);
    t.printed_bytes -= std::min(t.printed_bytes, t.printed.size() - kept.size());
    t.printed = kept;
  }

  // A test process that did not start, or whose sandbox could not be made: the harness never
  // ran, so nothing of the test is known.
  std::string fault_of_test(const Outcome& o) const {
    if (!o.start_error.empty()) return "the grader could not start a test: " + o.start_error;
    if (g_.isolation_.never_made(o))
      return "the grader could not make a test's sandbox: " + Isolation::why_never_made(o);
    return "";
  }

  void test_fault(const std::shared_ptr<TaskBuild>& b, TestResult& t, const std::string& fault) {
    b->result.fault = fault;
    t.passed = false;
    t.message = "not graded: " + fault;
    t.printed.clear();
    t.printed_bytes = 0;
    settle(b);
  }

  void settle(const std::shared_ptr<TaskBuild>& b) {
    if (--b->tests_open == 0) b->finish();
  }

  // --first-failure: the tests after `index`, never started, settled with `why`.
  void stop_after(const std::shared_ptr<TaskBuild>& b, int index, const std::string& why) {
    for (std::size_t i = std::size_t(index) + 1; i < b->result.tests.size(); ++i) {
      b->result.tests[i].message = why;
      settle(b);
    }
  }

  // The grader's own fault: the task is not graded (and says why), never scored 0.
  void fault_all(const std::shared_ptr<TaskBuild>& b, const std::string& why) {
    b->result.fault = why;
    for (TestResult& t : b->result.tests) {
      t.passed = false;
      t.message = "not graded: " + why;
    }
    b->finish();
  }

  // Why a command on a submission's files failed because of the grader rather than the code: it
  // could not be started, the sandbox could not be made, or the work folder is full. "" when the
  // failure is the code's.
  std::string fault_of(const Outcome& o, const std::string& what) const {
    if (!o.start_error.empty()) return "the grader could not run " + what + ": " + o.start_error;
    if (g_.isolation_.never_made(o))
      return "the grader could not make the sandbox for " + what + ": " +
             Isolation::why_never_made(o);
    return work_full();
  }

  std::string work_full() const { return work_folder_full(g_.settings_.work); }

  void fail_all(const std::shared_ptr<TaskBuild>& b, const std::string& problem) {
    b->result.problem = problem;
    for (TestResult& t : b->result.tests) {
      t.passed = false;
      t.message = problem.substr(0, problem.find('\n'));
    }
    b->finish();
  }
};

// One run of the pipeline over the submissions: each task's copy, a build per distinct copy (copies
// with the same digest, checked byte for byte, share one), the builds started a few at a time,
// and each submission's results as its tasks finish.
class Grader::Batch {
 public:
  Batch(const Grader& grader, Pipeline& pipeline, const std::vector<Submission>& submissions,
        const std::function<void(const SubmissionResult&, int)>& task_done,
        const std::function<void(const SubmissionResult&)>& submission_done)
      : results(submissions.size()),
        g_(grader),
        pipeline_(pipeline),
        submissions_(submissions),
        task_done_(task_done),
        submission_done_(submission_done),
        tasks_open_(submissions.size(), int(grader.settings_.tasks.size())),
        most_active_(2 * grader.settings_.jobs + 1) {}

  std::vector<SubmissionResult> results;  // by submission, filled as their tasks finish

  // Copies each task of submission i and queues its build (or joins an equal copy's).
  void add(std::size_t i) {
    results[i].submission = submissions_[i];
    // Named by number only: no submission's name ends up in a path a command sees.
    const fs::path copies = g_.settings_.work / "submissions" / std::to_string(i + 1);
    for (const int task : g_.settings_.tasks)
      add_task(i, task, copies);
  }

  // A few builds at a time, in the order of the submissions: enough to keep every process slot
  // busy, and the work folder holds the objects of these few only (each is removed when its
  // build is done), however large the class; the first submissions are done first.
  void start_next() {
    while (active_ < most_active_ && !waiting_.empty()) {
      std::shared_ptr<TaskBuild> next = waiting_.front();
      waiting_.pop_front();
      ++active_;
      next->on_finish.push_back([this] {
        --active_;
        start_next();
      });
      pipeline_.start(next);
    }
  }

 private:
  const Grader& g_;
  Pipeline& pipeline_;
  const std::vector<Submission>& submissions_;
  const std::function<void(const SubmissionResult&, int)>& task_done_;
  const std::function<void(const SubmissionResult&)>& submission_done_;
  std::vector<int> tasks_open_;
  std::map<std::pair<int, std::string>, std::vector<std::shared_ptr<TaskBuild>>> builds_;
  int build_count_ = 0;
  std::deque<std::shared_ptr<TaskBuild>> waiting_;
  int active_ = 0;
  const int most_active_;

  void add_task(std::size_t i, int task, const fs::path& copies) {
    if (!submissions_[i].fault.empty()) return not_graded(i, task, submissions_[i].fault);
    TaskCopy copy;
    try {
      copy = copy_task(submissions_[i], task, g_.kit_, copies);
    } catch (const fs::filesystem_error& error) {
      // The submission's files could not be read (gone, or not readable), or the work folder
      // not written: the grader's problem, never the student's grade. What was copied goes, so
      // that the others still have room.
      const std::string full = work_folder_full(g_.settings_.work);
      std::error_code ignored;
      fs::remove_all(copies / "tasks" / g_.kit_.task_folder(task), ignored);
      return not_graded(i, task,
                        full.empty()
                            ? "the grader could not copy the files: " + escaped(error.what())
                            : full + " (" + escaped(error.what()) + ")");
    }
    bool is_new = false;
    const std::shared_ptr<TaskBuild> b = build_of(task, copy, is_new);
    b->on_finish.push_back([this, i, task, b, notes = copy.notes] {
      TaskResult& r = results[i].tasks[task];
      r = b->result;
      r.task = task;
      r.notes = notes;
      done(i, task);
    });
    if (is_new) waiting_.push_back(b);
  }

  // The build of an equal copy graded already, or a new one (is_new).
  std::shared_ptr<TaskBuild> build_of(int task, const TaskCopy& copy, bool& is_new) {
    std::vector<std::shared_ptr<TaskBuild>>& same = builds_[{task, copy.digest}];
    std::shared_ptr<TaskBuild> b;
    if (copy.problem.empty())
      for (const auto& other : same)
        if (other->problem.empty() && same_files(other->copy, copy.folder)) b = other;
    if (b) return b;
    is_new = true;
    b = std::make_shared<TaskBuild>();
    b->task = task;
    b->copy = copy.folder;
    b->problem = copy.problem;
    b->folder = g_.settings_.work / "builds" / std::to_string(++build_count_);
    for (const std::string& file : g_.kit_.task_files.at(task))
      b->sources.push_back(fs::path(file).filename().string());
    same.push_back(b);
    // Its objects and libraries go as soon as its tests are done (the copy, small, stays to the
    // end: later copies are compared with it).
    if (!g_.settings_.keep_work)
      b->on_finish.push_back([folder = b->folder] {
        std::error_code error;
        fs::remove_all(folder, error);
      });
    return b;
  }

  // A task not graded because of the grader: every test failed, with why.
  void not_graded(std::size_t i, int task, const std::string& why) {
    TaskResult& r = results[i].tasks[task];
    r.task = task;
    r.fault = why;
    for (const TestInfo* test : tests_of_task(g_.tests_, task, g_.settings_.hidden)) {
      TestResult t;
      t.test = test;
      t.message = "not graded: " + why;
      r.tests.push_back(t);
    }
    done(i, task);
  }

  void done(std::size_t i, int task) {
    task_done_(results[i], task);
    if (--tasks_open_[i] == 0) submission_done_(results[i]);
  }
};

std::vector<SubmissionResult> Grader::run(
    const std::vector<Submission>& submissions, bool generous,
    const std::function<void(const SubmissionResult&, int)>& task_done,
    const std::function<void(const SubmissionResult&)>& submission_done) {
  ProcessPool pool(settings_.jobs);
  Pipeline pipeline(*this, pool, generous);
  Batch batch(*this, pipeline, submissions, task_done, submission_done);
  for (std::size_t i = 0; i < submissions.size(); ++i)
    batch.add(i);
  batch.start_next();
  pool.run();
  if (!settings_.keep_work) {
    std::error_code error;
    fs::remove_all(settings_.work / "submissions", error);
    fs::remove_all(settings_.work / "builds", error);
  }
  return std::move(batch.results);
}

std::vector<SubmissionResult> Grader::grade(
    const std::vector<Submission>& submissions,
    const std::function<void(const SubmissionResult&, int task)>& task_done,
    const std::function<void(const SubmissionResult&)>& submission_done) {
  return run(submissions, false, task_done, submission_done);
}

// The cache: a line "task N SIGNATURE" per task measured, "---", then "VARIANT SECONDS N NAME"
// per test. A task is measured when first graded and again once its programs change; a task
// not graded now keeps its lines as they are.
bool Grader::calibrate(const fs::path& cache,
                       const std::function<void(const std::string&)>& progress) {
  // A student release has no solutions/ to time: it carries the times the instructor's build
  // measured (another machine's, but the limits are ten times as long and at least 2 s).
  const bool shipped = kit_.solutions.empty();
  const CacheContents read = read_cache(shipped ? kit_.calibration : cache);
  // per task whose lines are kept
  std::map<int, std::string> signatures = take_cached(read, shipped, calibration_);
  if (shipped) return true;  // without times, every test gets the floor's ten times (grading.hpp)
  const std::vector<int> missing =
      tasks_to_measure(kit_, tests_, settings_.tasks, signatures, calibration_);
  if (missing.empty()) return true;
  take_measured(measure_reference(missing, progress).front(), calibration_);
  take_others(read_cache(cache), settings_.tasks, signatures, calibration_);
  return write_cache(cache, signatures, calibration_, progress);
}

std::vector<SubmissionResult> Grader::measure_reference(
    const std::vector<int>& missing, const std::function<void(const std::string&)>& progress) {
  const Settings saved = settings_;
  settings_.tasks = missing;
  settings_.hidden = true;  // one measurement serves a student's check and an instructor's grading
  // Every test, plainly and sanitized, whatever this run's mode: measured under --first-failure
  // (plainly, to the first failure) the cache would give every sanitized run the floor's limit.
  settings_.first_failure = false;
  settings_.work = saved.work / "reference";
  Submission reference = find_submission(kit_.solutions, kit_);
  reference.name = "reference";
  // Both runs of every test, however the plain one ends: each variant needs its time.
  const auto started = std::chrono::steady_clock::now();
  std::size_t measured = 0;
  if (progress)
    progress("measuring the reference's time per test, task" +
             std::string(missing.size() == 1 ? " " : "s ") +
             [&] {
               std::string list;
               for (const int task : missing)
                 list += (list.empty() ? "" : ", ") + std::to_string(task);
               return list;
             }() +
             " (once per build of the kit)");
  std::vector<SubmissionResult> results = run(
      {reference}, true,
      [&](const SubmissionResult&, int task) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        ++measured;
        if (progress)
          progress("  task " + std::to_string(task) + " measured (" + std::to_string(measured) +
                   " of " + std::to_string(missing.size()) + ", " +
                   std::to_string(std::lround(seconds)) + " s so far, about " +
                   std::to_string(std::lround(seconds / double(measured) *
                                              double(missing.size() - measured))) +
                   " s left)");
      },
      [](auto&) {});
  settings_ = saved;
  return results;
}

}  // namespace springlab::grader
