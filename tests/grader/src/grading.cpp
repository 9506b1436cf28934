#include "grading.hpp"

#include "checks.hpp"
#include "policy.hpp"
#include "verdict.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <memory>
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

}  // namespace

double TaskResult::points() const {
  double sum = 0.0;
  for (const TestResult& t : tests)
    sum += t.passed ? t.test->points : 0.0;
  return sum;
}

double TaskResult::max_points() const {
  double sum = 0.0;
  for (const TestResult& t : tests)
    sum += t.test->points;
  return sum;
}

int TaskResult::passed() const {
  return int(
      std::count_if(tests.begin(), tests.end(), [](const TestResult& t) { return t.passed; }));
}

double SubmissionResult::points() const {
  double sum = 0.0;
  for (const auto& [n, task] : tasks)
    sum += task.points();
  return sum;
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
  using Then = std::function<void(bool ok, const std::string& messages)>;
  // ok, the compiler's messages, and what the code may not include ("" when nothing).
  using Compiled = std::function<void(bool, const std::string&, const std::string&)>;

  // What compiling one file gave, kept for any later copy whose own files that the compiler read
  // are the same, byte for byte: a mutant, or a student's untouched file, is compiled once.
  struct Object {
    fs::path path;
    fs::path copy;                  // the copy it was compiled from
    std::vector<std::string> read;  // the copy's files the compiler read
    bool ok = false;
    std::string messages, problem;
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
                     {kit_.pch, {}, false}};
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

  // Preprocesses the task's files one at a time (each `-E`, in the sandbox) and checks what the
  // preprocessor made of them and which files they included; then compiles.
  void preprocess(const std::shared_ptr<TaskBuild>& b, std::size_t index,
                  std::vector<std::string> unchecked) {
    if (index == b->sources.size()) return compile_checked(b);
    const std::string& source = b->sources[index];
    const fs::path output = b->folder / (fs::path(source).stem().string() + ".ii");
    std::vector<std::string> argv = kit_.plain.compile;
    for (const std::string& arg : {std::string("-E"), std::string("-fpch-preprocess"),
                                   (b->copy / source).string(), std::string("-o"), output.string()})
      argv.push_back(arg);
    Command c = build_command(*b, std::move(argv), b->folder);
    pool_.add(std::move(c), [this, b, index, output, unchecked](Outcome o) mutable {
      // A file that does not preprocess does not compile either (and what was not checked is
      // never compiled): the preprocessor's messages say why.
      if (!o.exited || o.exit_code != 0) {
        std::string messages = stop_text(o.stopped, o.output) + o.start_error +
                               student_paths(o.output, b->copy, kit_.root);
        if (quotes_foreign_file(o.output, b->copy))
          messages =
              "(the compiler's messages are not shown: they quote a file that is not "
              "your submission's)\n";
        return fail_all(b, "does not compile:\n" + first_lines(messages, 60));
      }
      std::ifstream in(output);
      const Preprocessed p = check_preprocessed(in, include_roots(*b));
      if (p.breach) return fail_all(b, "not graded: " + p.breach->text());
      std::vector<std::string> fresh;
      for (const std::string& file : p.own_files)
        if (std::find(unchecked.begin(), unchecked.end(), file) == unchecked.end()) {
          unchecked.push_back(file);
          fresh.push_back(file);
        }
      if (const auto breach = check_sources(b->copy, fresh))
        return fail_all(b, "not graded: " + breach->text());
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
            [this, b](bool ok, const std::string& messages, const std::string& problem) {
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
      std::string messages, problem;
    };
    auto stage = std::make_shared<Stage>();
    stage->open = b->sources.size();
    for (const std::string& source : b->sources)
      compile_one(b, v, source, [stage, then](const Object& o) {
        stage->ok = stage->ok && o.ok;
        stage->messages += o.messages;
        if (stage->problem.empty()) stage->problem = o.problem;
        if (--stage->open == 0) then(stage->ok, first_lines(stage->messages, 60), stage->problem);
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
        if (o.ok) fs::copy_file(o.path, path, fs::copy_options::overwrite_existing);
        return done(o);
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
    pool_.add(std::move(c), [this, b, &v, source, key, path, done](Outcome outcome) {
      Object o;
      o.path = path;
      o.copy = b->copy;
      o.ok = outcome.exited && outcome.exit_code == 0;
      o.messages = stop_text(outcome.stopped, outcome.output) +
                   student_paths(outcome.output, b->copy, kit_.root);
      if (!outcome.start_error.empty()) o.messages += outcome.start_error + "\n";
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
      objects_[key].push_back(o);
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
    pool_.add(std::move(c), [this, b](Outcome o) {
      b->result.review = review_notes(o.output);
      const std::vector<std::string> problems = symbol_problems(o.output);
      if (!problems.empty()) {
        std::string text = "not graded:";
        for (const std::string& p : problems)
          text += "\n" + p;
        return fail_all(b, text);
      }
      link(b, kit_.plain, [this, b](bool ok, const std::string& messages) {
        if (!ok) return fail_all(b, "does not link:\n" + messages);
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
    pool_.add(std::move(c), [b, then, &kit = kit_](Outcome o) {
      then(o.exited && o.exit_code == 0,
           first_lines(student_paths(o.output, b->copy, kit.root), 30));
    });
  }

  void build_sanitized(const std::shared_ptr<TaskBuild>& b) {
    compile(b, kit_.sanitized, [this, b](bool ok, const std::string& messages, const std::string&) {
      if (!ok) return sanitized_ready(b, "it does not compile:\n" + messages);
      link(b, kit_.sanitized, [this, b](bool linked, const std::string& link_messages) {
        sanitized_ready(b, linked ? "" : "it does not link:\n" + link_messages);
      });
    });
  }

  void sanitized_ready(const std::shared_ptr<TaskBuild>& b, const std::string& problem) {
    b->sanitized_problem = problem;
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
    View view;
    view.bindings = {
        {kit_.programs.at(test.task), harness, false},
        {(sanitized ? kit_.sanitized_programs : kit_.programs).at(test.task), worker, false},
        {b.library(v), library, false}};
    view.scratch_mb = 16;
    g_.isolation_.confine(c, view);
    return c;
  }

  void run_plain(const std::shared_ptr<TaskBuild>& b, int index) {
    Command c = test_command(*b->result.tests[std::size_t(index)].test, kit_.plain, *b);
    const std::string secret = c.secret;
    const Limits limits = c.limits;
    pool_.add(std::move(c), [this, b, index, secret, limits](Outcome o) {
      TestResult& t = b->result.tests[std::size_t(index)];
      const RunVerdict v = judge(o, secret, limits, limits_text_);
      t.passed = v.passed;
      t.message = g_.settings_.raw ? v.message : without_raw_lines(v.message);
      t.printed = o.output;
      t.printed_bytes = o.output_bytes;
      t.seconds = o.wall_seconds;
      // A crash, or a failed check (an index out of Eigen's range, say), is run again with the
      // sanitizers, which can say what corrupted memory first.
      const bool crashed = !t.passed && (t.message.rfind("crashed: ", 0) == 0 ||
                                         t.message.rfind("a check failed", 0) == 0);
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
    if (!b->sanitized_problem.empty()) {
      if (crashed) return settle(b);
      plain.passed = false;
      plain.message = "passes, but the build with the sanitizers failed: " + b->sanitized_problem;
      return settle(b);
    }
    Command c = test_command(*plain.test, kit_.sanitized, *b);
    const std::string secret = c.secret;
    const Limits limits = c.limits;
    pool_.add(std::move(c), [this, b, index, secret, limits, crashed](Outcome o) {
      TestResult& t = b->result.tests[std::size_t(index)];
      t.sanitized_seconds = o.wall_seconds;
      const RunVerdict v = judge(o, secret, limits, limits_text_);
      if (crashed) {
        // Explained only when the sanitizers name a memory error or undefined behaviour, or a
        // failed check where the plain run only crashed.
        const bool explained =
            v.message.rfind("memory error", 0) == 0 ||
            v.message.rfind("undefined behaviour", 0) == 0 ||
            (v.message.rfind("a check failed", 0) == 0 && t.message.rfind("crashed: ", 0) == 0);
        if (!v.passed && explained) {
          t.message = t.message.substr(0, t.message.find('\n')) +
                      "; run again with the sanitizers, which check every memory access: " +
                      (g_.settings_.raw ? v.message : without_raw_lines(v.message));
          t.printed = o.output;
          t.printed_bytes = o.output_bytes;
          if (!g_.settings_.raw) without_sanitizer_report(t);
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

  void settle(const std::shared_ptr<TaskBuild>& b) {
    if (--b->tests_open == 0) b->finish();
  }

  void fail_all(const std::shared_ptr<TaskBuild>& b, const std::string& problem) {
    b->result.problem = problem;
    for (TestResult& t : b->result.tests) {
      t.passed = false;
      t.message = problem.substr(0, problem.find('\n'));
    }
    b->finish();
  }
};

std::vector<SubmissionResult> Grader::run(
    const std::vector<Submission>& submissions, bool generous,
    const std::function<void(const SubmissionResult&, int)>& task_done,
    const std::function<void(const SubmissionResult&)>& submission_done) {
  ProcessPool pool(settings_.jobs);
  Pipeline pipeline(*this, pool, generous);
  std::vector<SubmissionResult> results(submissions.size());
  std::vector<int> tasks_open(submissions.size(), int(settings_.tasks.size()));
  // Copies with the same digest, checked byte for byte: equal copies share one build.
  std::map<std::pair<int, std::string>, std::vector<std::shared_ptr<TaskBuild>>> builds;
  int build_count = 0;

  for (std::size_t i = 0; i < submissions.size(); ++i) {
    results[i].submission = submissions[i];
    const fs::path copies =
        settings_.work / "submissions" / (std::to_string(i + 1) + "-" + submissions[i].name);
    for (const int task : settings_.tasks) {
      TaskCopy copy = copy_task(submissions[i], task, kit_, copies);
      std::shared_ptr<TaskBuild> b;
      std::vector<std::shared_ptr<TaskBuild>>& same = builds[{task, copy.digest}];
      if (copy.problem.empty())
        for (const auto& other : same)
          if (other->problem.empty() && same_files(other->copy, copy.folder)) b = other;
      const bool is_new = !b;
      if (is_new) {
        b = std::make_shared<TaskBuild>();
        b->task = task;
        b->copy = copy.folder;
        b->problem = copy.problem;
        b->folder = settings_.work / "builds" / std::to_string(++build_count);
        for (const std::string& file : kit_.task_files.at(task))
          b->sources.push_back(fs::path(file).filename().string());
        same.push_back(b);
      }
      b->on_finish.push_back([&, i, task, b, notes = copy.notes] {
        TaskResult& r = results[i].tasks[task];
        r = b->result;
        r.task = task;
        r.notes = notes;
        task_done(results[i], task);
        if (--tasks_open[i] == 0) submission_done(results[i]);
      });
      if (is_new) pipeline.start(b);
    }
  }
  pool.run();
  return results;
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
void Grader::calibrate(const fs::path& cache) {
  // A student release has no solutions/ to time: it carries the times the instructor's build
  // measured (another machine's, but the limits are ten times as long and at least 2 s).
  const bool shipped = kit_.solutions.empty();
  std::map<int, std::string> signatures;  // per task whose lines are kept
  {
    std::ifstream in(shipped ? kit_.calibration : cache);
    std::string line;
    while (std::getline(in, line) && line != "---") {
      std::istringstream words(line);
      std::string word, signature;
      int task = 0;
      if (words >> word >> task >> signature && word == "task") signatures[task] = signature;
    }
    std::string variant, name;
    double seconds = 0;
    int task = 0;
    while (in >> variant >> seconds >> task && std::getline(in, name))
      if (signatures.count(task) > 0) calibration_[variant][name.substr(1)] = {task, seconds};
  }
  if (shipped) return;  // without times, every test gets the floor's ten times (grading.hpp)
  std::vector<int> missing;
  for (const int task : settings_.tasks) {
    const std::string signature = task_signature(kit_, tests_, task);
    if (signatures.count(task) > 0 && signatures[task] == signature) continue;
    for (auto& [variant, times] : calibration_)
      std::erase_if(times, [task](const auto& entry) { return entry.second.task == task; });
    signatures[task] = signature;
    missing.push_back(task);
  }
  if (missing.empty()) return;
  const Settings saved = settings_;
  settings_.tasks = missing;
  settings_.hidden = true;  // one measurement serves a student's check and an instructor's grading
  settings_.work = saved.work / "reference";
  Submission reference = find_submission(kit_.solutions, kit_);
  reference.name = "reference";
  // Both runs of every test, however the plain one ends: each variant needs its time.
  const std::vector<SubmissionResult> results = run(
      {reference}, true, [](auto&, int) {}, [](auto&) {});
  settings_ = saved;
  std::string failures;
  for (const auto& [task, result] : results.front().tasks)
    for (const TestResult& t : result.tests)
      if (!t.passed)
        failures += "\n  task " + std::to_string(task) + ": " + t.test->name + ": " +
                    (result.problem.empty() ? t.message : result.problem);
      else {
        calibration_["plain"][t.test->name] = {task, t.seconds};
        calibration_["sanitized"][t.test->name] = {task, t.sanitized_seconds};
      }
  if (!failures.empty())
    throw std::runtime_error(
        "the kit's own solutions fail tests, so nothing can be graded "
        "fairly (rebuild the kit; if it persists, the kit is broken):" +
        failures);
  // Written whole, then renamed: another grader reading it meanwhile sees the old or the new.
  const fs::path partial = cache.string() + "." + std::to_string(getpid());
  {
    std::ofstream out(partial);
    for (const auto& [task, signature] : signatures)
      out << "task " << task << ' ' << signature << '\n';
    out << "---\n";
    for (const auto& [name, variant] : calibration_)
      for (const auto& [test, time] : variant)
        out << name << ' ' << time.seconds << ' ' << time.task << ' ' << test << '\n';
  }
  std::error_code error;
  fs::rename(partial, cache, error);
}

}  // namespace springlab::grader
