// The grader's proof, in one batch as CI runs it (label grader): the starter code scores nothing
// and says what to write, the solutions score everything, every mutant (tests/mutants/*.patch,
// graded apart by the [mutants] case at the end) loses points in its own task and in no other,
// by failing a public test, and every hostile or broken submission (tests/grader/hostile/*/, see
// expect.toml there) gets the score and the feedback it must; the submissions and the kit's sources
// on disk are unchanged afterwards, and no report grows large. When the kit has hidden tests
// (tests/hidden/), they are graded too, reported as hidden, and each mutant in
// tests/hidden/mutants/ passes every public test of its task and fails a hidden one: the reason
// those tests exist.
#include "lab_catch.hpp"
#include "process.hpp"
#include "reports.hpp"

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using namespace springlab::grader;

namespace {

const fs::path kit = SPRINGLAB_SOURCE_DIR;
const fs::path batch = SPRINGLAB_BATCH_DIR;
const fs::path submissions = batch / "submissions";

enum class Points { full, none, some, less };

// Which of its task's tests a mutant must fail: at least one public test (what a student sees
// before the due date), or hidden tests only (tests/hidden/mutants/).
enum class CaughtBy { any, public_tests, hidden_only };

struct Expectation {
  std::string name;  // the submission's folder, and its row in the gradebook
  std::string what;
  std::map<int, Points> points;         // per task
  std::map<int, std::string> feedback;  // per task: a regex its feedback must match
  CaughtBy caught_by = CaughtBy::any;
  int task = 0;  // a mutant's task
  // A mutant's "Expect:" lines: what its task's first failure must say (each one, word for word).
  std::vector<std::string> first_failure;
};

const fs::path hidden_tests = kit / "tests" / "hidden";

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every file under `folder`, its path and bytes: equal before and after exactly when nothing
// was written, added or removed.
std::string snapshot(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) files[entry.path().string()] = read(entry.path());
  std::string text;
  for (const auto& [path, bytes] : files)
    text += path + '\0' + bytes + '\0';
  return text;
}

// Runs a trusted program (the grader, patch) and returns its exit status and output.
std::pair<int, std::string> run(std::vector<std::string> argv, const fs::path& folder = batch) {
  ProcessPool pool(1);
  Command c;
  c.argv = std::move(argv);
  c.env = plain_environment();
  // A value of the grader's own environment that no test process may ever see (the
  // read-grader-environment case looks for it).
  c.env.push_back("SPRINGLAB_BATCH_SECRET=batch-secret-7f1c");
  c.directory = folder.string();
  c.limits.wall_seconds = c.limits.cpu_seconds = 3600;
  c.limits.address_space_mb = 0;
  c.limits.file_size_mb = 4096;
  std::pair<int, std::string> result{-1, ""};
  pool.add(std::move(c), [&](Outcome o) {
    result = {o.exited ? o.exit_code : 128 + o.signal, o.start_error + o.output};
  });
  pool.run();
  return result;
}

// The kit's file names (spring_damper.cpp) and the task folder each belongs in.
std::map<std::string, std::string> kit_files() {
  std::map<std::string, std::string> files;
  for (const auto& folder : fs::directory_iterator(kit / "solutions"))
    for (const auto& file : fs::directory_iterator(folder.path()))
      files[file.path().filename().string()] = folder.path().filename().string();
  return files;
}

Points parse_points(const std::string& text, const std::string& where) {
  if (text == "full") return Points::full;
  if (text == "none") return Points::none;
  if (text == "some") return Points::some;
  if (text == "less") return Points::less;
  FAIL(where << ": points = \"" << text << "\": one of full, none, some, less");
  return Points::none;
}

Expectation all(const std::string& name, const std::string& what, Points points) {
  Expectation e;
  e.name = name;
  e.what = what;
  for (int task = 1; task <= 5; ++task)
    e.points[task] = points;
  return e;
}

// A case's file, with @KIT@ replaced by the kit's folder (cases that name the kit's files by
// their absolute path work wherever the kit is).
void write_case_file(const fs::path& from, const fs::path& to) {
  std::string text = read(from);
  const std::string placeholder = "@KIT@";
  for (auto at = text.find(placeholder); at != std::string::npos; at = text.find(placeholder, at))
    text.replace(at, placeholder.size(), kit.string());
  std::ofstream(to, std::ios::binary) << text;
}

// A hostile case: its base (solutions/ or the starter code) with the case's files over it.
Expectation hostile(const fs::path& folder) {
  const fs::path expect_file = folder / "expect.toml";
  toml::table expect;
  try {
    expect = toml::parse_file(expect_file.string());
  } catch (const toml::parse_error& error) {
    FAIL(expect_file << ": " << error.description());
  }
  const std::string base = expect["base"].value_or(std::string("solutions"));
  REQUIRE((base == "solutions" || base == "starter"));
  Expectation e = all(folder.filename().string(), expect["what"].value_or(std::string("?")),
                      base == "solutions" ? Points::full : Points::none);
  const fs::path target = submissions / e.name;
  fs::copy(kit / (base == "solutions" ? "solutions" : "tasks"), target,
           fs::copy_options::recursive);
  const std::map<std::string, std::string> known = kit_files();
  std::vector<std::string> touched, helpers;
  for (const auto& file : fs::directory_iterator(folder)) {
    const std::string name = file.path().filename().string();
    if (name == "expect.toml") continue;
    if (known.count(name) > 0) {
      write_case_file(file.path(), target / known.at(name) / name);
      touched.push_back(known.at(name));
    } else {
      helpers.push_back(name);
    }
  }
  for (const std::string& helper : helpers)
    for (const std::string& task_folder : touched)
      write_case_file(folder / helper, target / task_folder / helper);
  // [links]: a path in the submission that is a symbolic link (to @KIT@/... or elsewhere).
  if (const toml::table* links = expect["links"].as_table())
    for (const auto& [path, to] : *links) {
      std::string where = to.value_or(std::string());
      if (where.rfind("@KIT@", 0) == 0) where = kit.string() + where.substr(5);
      fs::remove_all(target / std::string(path.str()));
      fs::create_symlink(where, target / std::string(path.str()));
    }
  for (int task = 1; task <= 5; ++task) {
    const std::string key = "task" + std::to_string(task);
    if (const auto points = expect[key]["points"].value<std::string>())
      e.points[task] = parse_points(*points, expect_file.string() + " [" + key + "]");
    if (const auto feedback = expect[key]["feedback"].value<std::string>())
      e.feedback[task] = *feedback;
  }
  return e;
}

// A mutant: the solutions with one patch applied; its own task loses points, no other does.
Expectation mutant(const fs::path& patch, CaughtBy caught_by, const fs::path& into = submissions) {
  const std::string text = read(patch);
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex(R"(\n\+\+\+ b/(task\d)[^/]*/)")));
  const int task = m[1].str()[4] - '0';
  const std::string prefix = caught_by == CaughtBy::hidden_only ? "hidden-mutant-" : "mutant-";
  Expectation e =
      all(prefix + patch.stem().string(), "the mutant " + patch.filename().string(), Points::full);
  e.points[task] = Points::less;
  e.caught_by = caught_by;
  e.task = task;
  // The header (the lines before the diff) names the words its first failure must say.
  std::istringstream header(text.substr(0, text.find("\n--- a/")));
  for (std::string line; std::getline(header, line);)
    if (line.rfind("Expect: ", 0) == 0) e.first_failure.push_back(line.substr(8));
  INFO(
      patch.filename().string() << " needs a line 'Expect: WORDS' in its header: words of the "
                                   "first failure that name the mistake (tests/mutants/README.md)");
  CHECK_FALSE(e.first_failure.empty());
  const fs::path target = into / e.name;
  fs::copy(kit / "solutions", target, fs::copy_options::recursive);
  // Run from `into`, never from the [batch] case's folder, which that case empties at its start
  // while the [mutants] case may be making its copies beside it.
  const auto [status, output] = run(
      {SPRINGLAB_PATCH, "--fuzz=0", "--silent", "-p1", "-d", target.string(), "-i", patch.string()},
      into);
  INFO(output);
  REQUIRE(status == 0);
  return e;
}

// The points of each task in the gradebook, by submission.
std::map<std::string, std::vector<double>> read_gradebook(const fs::path& file) {
  std::map<std::string, std::vector<double>> rows;
  std::istringstream lines(read(file));
  std::string line;
  std::getline(lines, line);
  REQUIRE(line == "submission,task1,task2,task3,task4,task5,total");
  while (std::getline(lines, line)) {
    std::istringstream cells(line);
    std::string name, cell;
    std::getline(cells, name, ',');
    std::vector<double> points;
    while (std::getline(cells, cell, ','))
      points.push_back(std::stod(cell));
    rows[name] = points;
  }
  return rows;
}

// Task `task`'s part of a feedback text.
std::string section(const std::string& feedback, int task) {
  const std::string heading = "==> Task " + std::to_string(task) + ":";
  const auto start = feedback.find(heading);
  if (start == std::string::npos) return "";
  const auto end = feedback.find("==> ", start + heading.size());
  return feedback.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// The first failed test of a task's feedback: its "... FAIL" line and the lines of explanation
// under it.
std::string first_failure(const std::string& task_feedback) {
  std::istringstream lines(task_feedback);
  std::string block;
  for (std::string line; std::getline(lines, line);) {
    if (block.empty()) {
      // "NAME ... FAIL", or "NAME ... FAIL (hidden test: ...)"
      if (std::regex_search(line, std::regex(R"( \.\.\. FAIL( \(.*\))?$)"))) block = line;
    } else if (line.rfind("        ", 0) == 0) {
      block += "\n" + line;
    } else {
      break;
    }
  }
  return block;
}

// The kit's solutions/ and tasks/, to compare before and after a grading.
std::string kit_sources() {
  return snapshot(kit / "solutions") + snapshot(kit / "tasks");
}

// A teacher's words: no Catch2 expression and no path into the kit's tests/ (--raw shows them
// to instructors).
bool has_raw_lines(const std::string& feedback) {
  return std::regex_search(feedback, std::regex(R"(with values:|tests/\S+\.cpp:\d+)"));
}

// Every report (a regular file) under `folder` stays under 1 MiB.
void check_report_sizes(const fs::path& folder) {
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) {
      INFO(entry.path());
      CHECK(entry.file_size() < (1u << 20));
    }
}

}  // namespace

TEST_CASE(
    "One batch grades the starter code, the solutions, the hidden tests' mutants and the hostile "
    "submissions as each must be graded",
    "[batch]") {
  fs::remove_all(batch);
  fs::create_directories(submissions);
  std::vector<Expectation> expected;
  fs::copy(kit / "tasks", submissions / "starter", fs::copy_options::recursive);
  expected.push_back(all("starter", "the starter code", Points::none));
  fs::copy(kit / "solutions", submissions / "solutions", fs::copy_options::recursive);
  expected.push_back(all("solutions", "the solutions", Points::full));
  // The public tests' mutants (tests/mutants/) are graded apart, by the [mutants] case below.
  if (fs::is_directory(hidden_tests / "mutants"))
    for (const auto& entry : fs::directory_iterator(hidden_tests / "mutants"))
      if (entry.path().extension() == ".patch")
        expected.push_back(mutant(entry.path(), CaughtBy::hidden_only));
  for (const auto& entry : fs::directory_iterator(kit / "tests" / "grader" / "hostile"))
    if (entry.is_directory()) expected.push_back(hostile(entry.path()));

  std::map<std::string, std::string> before;
  std::vector<std::string> argv = {SPRINGLAB_GRADE, "--out", (batch / "results").string(), "--work",
                                   (batch / "work").string()};
  for (const Expectation& e : expected) {
    before[e.name] = snapshot(submissions / e.name);
    argv.push_back((submissions / e.name).string());
  }
  const std::string kit_before = kit_sources();
  const auto start = std::chrono::steady_clock::now();
  const auto [status, output] = run(argv);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "grader.batch: " << expected.size() << " submissions graded in " << seconds
            << " s of wall time (" << seconds / double(expected.size())
            << " s each), the reference's times measured once per build\n";
  // The grader's own table of where that time went, for ./lab test's summary (issue 27).
  const std::size_t table = output.find("springlab-grade: the processes of this run");
  CHECK(table != std::string::npos);
  if (table != std::string::npos) {
    std::istringstream lines(output.substr(table));
    std::string line;
    std::getline(lines, line);
    while (std::getline(lines, line) && line.rfind("  ", 0) == 0)
      std::cout << "grader.batch:" << line << '\n';
  }
  INFO(output);
  REQUIRE(status == 0);

  const auto rows = read_gradebook(batch / "results" / "gradebook.csv");
  REQUIRE(rows.count("solutions") == 1);
  // The most each task gives: the sum of its tests' max_score in the solutions' results.
  std::vector<double> most(6, 0.0);
  const auto solutions =
      nlohmann::json::parse(read(batch / "results" / "solutions" / "results.json"));
  for (const auto& test : solutions["tests"])
    most[std::size_t(test["tags"][0].get<std::string>()[4] - '0')] +=
        test["max_score"].get<double>();
  for (int task = 1; task <= 5; ++task)
    REQUIRE(most[std::size_t(task)] > 0);

  for (const Expectation& e : expected) {
    INFO(e.name << ": " << e.what);
    REQUIRE(rows.count(e.name) == 1);
    const std::string feedback = read(batch / "results" / results_folder(e.name) / "feedback.txt");
    for (const auto& [task, want] : e.points) {
      const double got = rows.at(e.name)[std::size_t(task - 1)];
      const double full = most[std::size_t(task)];
      INFO("task " << task << ": " << got << " of " << full << " points\n"
                   << section(feedback, task));
      switch (want) {
        case Points::full:
          CHECK(got == full);
          break;
        case Points::none:
          CHECK(got == 0.0);
          break;
        case Points::some:
          CHECK((got > 0.0 && got < full));
          break;
        case Points::less:
          CHECK(got < full);
          break;
      }
    }
    if (e.caught_by != CaughtBy::any) {
      // Its task's tests in its results.json: public ones are "visible", hidden ones shown
      // "after_due_date".
      const auto results =
          nlohmann::json::parse(read(batch / "results" / results_folder(e.name) / "results.json"));
      int public_failed = 0, hidden_failed = 0;
      for (const auto& test : results["tests"])
        if (test["tags"][0] == "task" + std::to_string(e.task) && test["status"] == "failed")
          ++(test["visibility"] == "visible" ? public_failed : hidden_failed);
      INFO("task " << e.task << ": " << public_failed << " public and " << hidden_failed
                   << " hidden tests failed\n"
                   << section(feedback, e.task));
      if (e.caught_by == CaughtBy::public_tests) CHECK(public_failed > 0);
      if (e.caught_by == CaughtBy::hidden_only) CHECK((public_failed == 0 && hidden_failed > 0));
    }
    for (const std::string& words : e.first_failure) {
      const std::string first = first_failure(section(feedback, e.task));
      INFO("the first failure must say \"" << words << "\":\n" << first);
      CHECK(first.find(words) != std::string::npos);
    }
    for (const auto& [task, pattern] : e.feedback) {
      INFO("task " << task << " feedback must match /" << pattern << "/:\n"
                   << section(feedback, task));
      CHECK(std::regex_search(section(feedback, task), std::regex(pattern)));
    }
    CHECK_FALSE(has_raw_lines(feedback));
    CHECK(snapshot(submissions / e.name) == before[e.name]);
  }

  // The hidden tests, when the kit has them: in every task, shown after the due date, tagged and
  // marked in the feedback; the public ones visible.
  if (fs::is_directory(hidden_tests)) {
    std::vector<int> hidden(6, 0);
    for (const auto& test : solutions["tests"]) {
      const auto& tags = test["tags"];
      const bool tagged = std::find(tags.begin(), tags.end(), "hidden") != tags.end();
      INFO(test["name"].get<std::string>());
      CHECK(test["visibility"] == (tagged ? "after_due_date" : "visible"));
      hidden[std::size_t(tags[0].get<std::string>()[4] - '0')] += tagged;
    }
    for (int task = 1; task <= 5; ++task) {
      INFO("task " << task << " has no hidden test");
      CHECK(hidden[std::size_t(task)] > 0);
    }
    const std::string feedback = read(batch / "results" / "solutions" / "feedback.txt");
    CHECK_THAT(feedback, lab_catch::Contains(std::string("... pass ") + hidden_mark));
  }
  // The starter code fails every test by saying what to write.
  const auto starter = nlohmann::json::parse(read(batch / "results" / "starter" / "results.json"));
  for (const auto& test : starter["tests"]) {
    INFO(test["name"].get<std::string>() << ": " << test["output"].get<std::string>());
    CHECK(test["status"] == "failed");
    CHECK(test["output"].get<std::string>().find("is not implemented yet") != std::string::npos);
  }
  CHECK(kit_sources() == kit_before);
  check_report_sizes(batch / "results");
}

// The mutants of tests/mutants/, each graded in its own task only, that task's tests in order and
// stopped at the first failure (springlab-grade --first-failure, as .ci/mutants grades the
// generated ones, one process at a time beside grader.batch). A mutant whose run there does not
// show what is expected (it passes every test plainly, as a use after scope that only
// AddressSanitizer sees may, or a hidden test or other words fail first) is graded again in its
// task through the whole pipeline, sanitizers included, as a student's check runs it, and judged
// on that. Until issue 27 the [batch] case graded every mutant as a whole submission, five tasks
// through the whole pipeline: 43 of its 101 submissions and most of its sanitized runs.
// What it proved is proved here from less: the mutant's task loses points by a public test whose
// feedback, the first failure, says the words its header expects. That no other task loses any
// follows from the patch: it changes files of its own task's folder only (checked), a task is
// built from its own folder alone, and the other folders are the solutions' bytes, which the
// [batch] case grades with full points. No longer run: the tests a mutant passes plainly, again
// under the sanitizers, when its first failure is already as expected (the solutions and the
// hostile submissions still take that path).
TEST_CASE("Each mutant loses points in its own task, first by a public test that names the mistake",
          "[mutants]") {
  const fs::path folder = batch.parent_path() / "batch-mutants";
  const fs::path into = folder / "submissions";
  fs::remove_all(folder);
  fs::create_directories(into);
  std::map<int, std::vector<Expectation>> by_task;
  std::map<std::string, std::string> before;
  for (const auto& entry : fs::directory_iterator(kit / "tests" / "mutants")) {
    if (entry.path().extension() != ".patch") continue;
    Expectation e = mutant(entry.path(), CaughtBy::public_tests, into);
    const std::string text = read(entry.path());
    const std::regex changed(R"(\n(?:---|\+\+\+) [ab]/([^\n]+))");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), changed);
         it != std::sregex_iterator(); ++it) {
      INFO(entry.path().filename().string() << " changes " << (*it)[1].str());
      CHECK((*it)[1].str().rfind("task" + std::to_string(e.task) + "_", 0) == 0);
    }
    before[e.name] = snapshot(into / e.name);
    by_task[e.task].push_back(std::move(e));
  }
  REQUIRE_FALSE(by_task.empty());
  const std::string kit_before = kit_sources();

  // Grades `mutants` in `task` (to the first failure, or through the whole pipeline) and returns
  // the results folder.
  const auto grade = [&](int task, const std::vector<Expectation>& mutants, bool first) {
    const fs::path results =
        folder / ((first ? "first-failure-task" : "whole-task") + std::to_string(task));
    std::vector<std::string> argv = {SPRINGLAB_GRADE,
                                     "--jobs",
                                     "1",
                                     "--tasks",
                                     std::to_string(task),
                                     "--out",
                                     results.string(),
                                     "--work",
                                     (folder / "work").string()};
    if (first) argv.push_back("--first-failure");
    for (const Expectation& e : mutants)
      argv.push_back((into / e.name).string());
    const auto [status, output] = run(argv, folder);
    INFO(output);
    REQUIRE(status == 0);
    return results;
  };
  // What a mutant's grading showed in its task: every failed expectation, in words ("" when it
  // is as expected).
  const auto judged = [](const fs::path& results, const Expectation& e) {
    double got = 0, most = 0;
    int public_failed = 0;
    const auto json = nlohmann::json::parse(read(results / "results.json"));
    for (const auto& test : json["tests"]) {
      if (test["tags"][0] != "task" + std::to_string(e.task)) continue;
      got += test["score"].get<double>();
      most += test["max_score"].get<double>();
      public_failed += test["status"] == "failed" && test["visibility"] == "visible" &&
                       test["output"].get<std::string>().find("not run: the grading stopped") ==
                           std::string::npos;
    }
    std::ostringstream wrong;
    if (!(most > 0 && got < most))
      wrong << "\n  it lost no point (" << got << " of " << most << ")";
    if (public_failed == 0) wrong << "\n  no public test failed";
    const std::string first = first_failure(section(read(results / "feedback.txt"), e.task));
    if (first.find(hidden_mark) != std::string::npos) wrong << "\n  a hidden test failed first";
    for (const std::string& words : e.first_failure)
      if (first.find(words) == std::string::npos)
        wrong << "\n  the first failure does not say \"" << words << "\"";
    if (!wrong.str().empty()) wrong << "\n  its first failure:\n" << first;
    return wrong.str();
  };

  const auto start = std::chrono::steady_clock::now();
  std::size_t count = 0, again = 0;
  for (const auto& [task, mutants] : by_task) {
    count += mutants.size();
    // Each mutant's results folder, what its grading there showed ("" when as expected), and
    // whether that was the whole pipeline.
    struct Graded {
      fs::path results;
      std::string wrong;
      bool whole = false;
    };
    std::map<std::string, Graded> graded;
    std::vector<Expectation> unclear;
    const fs::path first = grade(task, mutants, true);
    for (const Expectation& e : mutants) {
      const fs::path mine = first / results_folder(e.name);
      graded[e.name] = {mine, judged(mine, e)};
      if (!graded[e.name].wrong.empty()) unclear.push_back(e);
    }
    if (!unclear.empty()) {
      const fs::path whole = grade(task, unclear, false);
      for (const Expectation& e : unclear) {
        const fs::path mine = whole / results_folder(e.name);
        graded[e.name] = {mine, judged(mine, e), true};
      }
    }
    again += unclear.size();
    for (const Expectation& e : mutants) {
      const Graded& g = graded[e.name];
      INFO(e.name << ": " << e.what
                  << (g.whole ? ", graded through the whole pipeline"
                              : ", graded to its first failure"));
      CHECK(g.wrong == "");
      CHECK_FALSE(has_raw_lines(read(g.results / "feedback.txt")));
      CHECK(snapshot(into / e.name) == before[e.name]);
    }
  }
  CHECK(kit_sources() == kit_before);
  for (const auto& results : fs::directory_iterator(folder))
    if (results.path() != into && results.path() != folder / "work")
      check_report_sizes(results.path());
  // The reference's times these gradings used (the build's cache, measured by grader.calibration
  // before them; tests/calibration.sh checks what a grading to the first failure measures): both
  // variants of every test, none zero, or the other graders' limits would be the floor's.
  std::istringstream cache(read(fs::path(SPRINGLAB_GRADE).parent_path() / "calibration.txt"));
  std::string line;
  while (std::getline(cache, line) && line != "---") {
  }
  std::map<std::string, int> variants;
  for (std::string variant; cache >> variant;) {
    double seconds = 0;
    cache >> seconds;
    std::getline(cache, line);
    INFO("calibration.txt: " << variant << ' ' << seconds << line);
    CHECK(seconds > 0);
    ++variants[variant];
  }
  CHECK(variants["plain"] > 0);
  CHECK(variants["sanitized"] == variants["plain"]);
  std::cout << "grader.mutants: the " << count
            << " mutants of tests/mutants graded apart, each in its own task to its first failure, "
            << again << " of them again through the whole pipeline, in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s of wall time\n";
}
