// springlab-gradescope-check: checks a results.json written by run_autograder against Gradescope's
// format and against what the submission should score (.ci/autograder runs it). Every field
// Gradescope reads must be there with its type; every test is tagged with its task, has a status
// that agrees with its score and a visibility Gradescope knows, and the tests add up to the total.
// Prints one line per task and exits 0, or names each field that is wrong and exits 1.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace {

using nlohmann::json;

struct Tally {
  double score = 0.0, max_score = 0.0;
  int passed = 0, failed = 0, hidden = 0;
};

class Checker {
 public:
  void fail(const std::string& what) { problems_.push_back(what); }
  bool ok() const { return problems_.empty(); }
  void report() const {
    for (const std::string& p : problems_)
      std::cerr << "springlab-gradescope-check: " << p << '\n';
  }

  // The field `key` of `object` (named `where`) when it has the type `is` checks, else null.
  const json* field(const json& object, const std::string& where, const std::string& key,
                    bool (json::*is)() const noexcept, const std::string& type) {
    const auto it = object.find(key);
    if (it == object.end()) {
      fail(where + "." + key + " is missing (" + type + " expected)");
      return nullptr;
    }
    if (!((*it).*is)()) {
      fail(where + "." + key + " = " + it->dump() + ": " + type + " expected");
      return nullptr;
    }
    return &*it;
  }

 private:
  std::vector<std::string> problems_;
};

// "taskN" for the test named "Task N: ..." (the grader's names), or "" when it names none.
std::string task_of(const std::string& name) {
  if (name.size() > 7 && name.rfind("Task ", 0) == 0 && name[5] >= '1' && name[5] <= '5' &&
      name[6] == ':')
    return std::string("task") + name[5];
  return "";
}

// Equal to the hundredth of a point the grader rounds totals to.
bool close(double a, double b) {
  return std::abs(a - b) < 0.006;
}

struct Options {
  std::string file, expect = "any";
  int except_task = 0;
  std::vector<std::string> mentions;
  bool hidden = false;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("results", o.file, "the results.json to check")->required();
  app.add_option("--expect", o.expect,
                 "full: every test passes; zero: every test fails; broken: grading failed "
                 "(score 0, no tests, says so); any")
      ->check(CLI::IsMember({"full", "zero", "broken", "any"}))
      ->capture_default_str();
  app.add_option("--except-task", o.except_task,
                 "with --expect full: this task's tests may fail, and one at least must")
      ->check(CLI::Range(1, 5));
  app.add_option("--output-mentions", o.mentions, "text the top-level output must contain");
  app.add_flag("--hidden", o.hidden,
               "every task has hidden tests: visibility after_due_date and the tag hidden, "
               "which no visible test has");
}

// The file as JSON, or nothing (said on stderr) when it cannot be read or is not JSON.
std::optional<json> read_results(const std::string& file) {
  try {
    std::ifstream in(file);
    if (!in) {
      std::cerr << "springlab-gradescope-check: cannot read " << file << '\n';
      return std::nullopt;
    }
    return json::parse(in);
  } catch (const json::exception& error) {
    std::cerr << "springlab-gradescope-check: " << file << " is not JSON: " << error.what() << '\n';
    return std::nullopt;
  }
}

// The top level's fields Gradescope reads (null where missing or of the wrong type).
struct TopLevel {
  const json* score = nullptr;
  const json* output = nullptr;
  const json* tests = nullptr;
};

TopLevel check_top_level(Checker& c, const json& results) {
  const std::set<std::string> visibilities = {"hidden", "after_due_date", "after_published",
                                              "visible"};
  TopLevel top;
  top.score = c.field(results, "results", "score", &json::is_number, "a number");
  c.field(results, "results", "execution_time", &json::is_number, "a number of seconds");
  top.output = c.field(results, "results", "output", &json::is_string, "a string");
  if (const json* v =
          c.field(results, "results", "stdout_visibility", &json::is_string, "a string"))
    if (visibilities.count(v->get<std::string>()) == 0)
      c.fail("results.stdout_visibility = " + v->dump() + ": one of hidden, after_due_date, " +
             "after_published, visible expected");
  top.tests = c.field(results, "results", "tests", &json::is_array, "an array");
  return top;
}

// The tally of every test, and of each task's.
struct Tallies {
  std::map<std::string, Tally> tasks;
  Tally all;
};

// Test i: its fields, its task's tag, a status that agrees with its score, a visibility
// Gradescope knows (and with --hidden, the tag hidden exactly when it is after_due_date); counted.
void check_test(Checker& c, const json& t, std::size_t i, bool hidden, Tallies& tallies) {
  const std::string where = "tests[" + std::to_string(i) + "]";
  if (!t.is_object()) return c.fail(where + ": an object expected");
  const json* name = c.field(t, where, "name", &json::is_string, "a string");
  const json* s = c.field(t, where, "score", &json::is_number, "a number");
  const json* max = c.field(t, where, "max_score", &json::is_number, "a number");
  const json* status = c.field(t, where, "status", &json::is_string, "a string");
  c.field(t, where, "output", &json::is_string, "a string");
  const json* tags = c.field(t, where, "tags", &json::is_array, "an array of strings");
  const json* visibility = c.field(t, where, "visibility", &json::is_string, "a string");
  if (name == nullptr || s == nullptr || max == nullptr || status == nullptr || tags == nullptr ||
      visibility == nullptr)
    return;
  const std::string n = name->get<std::string>(), st = status->get<std::string>();
  const std::string task = task_of(n);
  const double points = s->get<double>(), most = max->get<double>();
  if (task.empty()) c.fail(where + ".name = " + name->dump() + ": \"Task N: ...\" expected");
  bool tagged = false;
  for (const json& tag : *tags)
    if (!tag.is_string())
      c.fail(where + ".tags holds " + tag.dump() + ": strings expected");
    else
      tagged = tagged || tag.get<std::string>() == task;
  if (!task.empty() && !tagged)
    c.fail(where + ".tags = " + tags->dump() + ": " + task + " expected, for " + name->dump());
  if (st != "passed" && st != "failed")
    c.fail(where + ".status = " + status->dump() + ": \"passed\" or \"failed\" expected");
  const std::string vis = visibility->get<std::string>();
  const bool tagged_hidden = std::any_of(tags->begin(), tags->end(), [](const json& tag) {
    return tag.is_string() && tag.get<std::string>() == "hidden";
  });
  if (hidden && tagged_hidden != (vis == "after_due_date"))
    c.fail(where + " (" + n + "): visibility " + vis + " with tags " + tags->dump() +
           ": the tag hidden exactly when the visibility is after_due_date");
  if (vis != "visible" && vis != "after_due_date")
    c.fail(where + ".visibility = " + visibility->dump() +
           ": \"visible\" or \"after_due_date\" expected");
  if (points < 0 || most < 0 || points > most)
    c.fail(where + ": score " + s->dump() + " of max_score " + max->dump() +
           ": 0 <= score <= max_score expected");
  if (st == "passed" && points != most)
    c.fail(where + " passed with " + s->dump() + " of " + max->dump() + " points");
  for (Tally* x : {&tallies.tasks[task], &tallies.all}) {
    x->score += points;
    x->max_score += most;
    (st == "passed" ? x->passed : x->failed) += 1;
    x->hidden += vis == "after_due_date" ? 1 : 0;
  }
}

// --expect full or zero: the tests' statuses and the score, task by task.
void check_full_or_zero(Checker& c, const Options& o, const Tallies& tallies, double total,
                        std::size_t count) {
  if (count == 0) c.fail("no tests in results.tests");
  for (const auto& [task, tally] : tallies.tasks) {
    const bool excepted = task == "task" + std::to_string(o.except_task);
    if (o.expect == "zero" && tally.passed > 0)
      c.fail(task + ": " + std::to_string(tally.passed) + " tests passed, none expected");
    if (o.expect == "full" && !excepted && tally.failed > 0)
      c.fail(task + ": " + std::to_string(tally.failed) + " tests failed, none expected");
    if (o.expect == "full" && excepted && tally.failed == 0)
      c.fail(task + ": every test passed, but some should fail");
  }
  if (o.expect == "full" && o.except_task == 0 &&
      !(total > 0 && close(total, tallies.all.max_score)))
    c.fail("score " + std::to_string(total) + " of " + std::to_string(tallies.all.max_score) +
           ": full marks expected");
  if (o.expect == "zero" && total != 0.0) c.fail("score " + std::to_string(total) + ": 0 expected");
}

// What the options expect of the whole: the score, the tests, hidden tests, the output's words.
void check_expected(Checker& c, const Options& o, Tallies& tallies, double total, std::size_t count,
                    const std::string& text) {
  if (o.expect == "full" || o.expect == "zero") check_full_or_zero(c, o, tallies, total, count);
  if (o.hidden)
    for (int n = 1; n <= 5; ++n)
      if (tallies.tasks["task" + std::to_string(n)].hidden == 0)
        c.fail("task" + std::to_string(n) + " has no hidden test (visibility after_due_date)");
  if (o.expect == "broken") {
    if (total != 0.0) c.fail("score " + std::to_string(total) + ": 0 expected");
    if (count != 0) c.fail(std::to_string(count) + " tests: none expected when grading failed");
    if (text.find("could not grade") == std::string::npos)
      c.fail("results.output does not say that grading failed: " + json(text).dump());
  }
  for (const std::string& m : o.mentions)
    if (text.find(m) == std::string::npos)
      c.fail("results.output does not mention " + json(m).dump() + ": " + json(text).dump());
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("springlab-gradescope-check: checks a results.json from run_autograder");
  add_options(app, o);
  CLI11_PARSE(app, argc, argv);

  const std::optional<json> results = read_results(o.file);
  if (!results) return 1;
  Checker c;
  if (!results->is_object()) {
    std::cerr << "springlab-gradescope-check: " << o.file << ": an object expected\n";
    return 1;
  }
  const TopLevel top = check_top_level(c, *results);
  Tallies tallies;
  if (top.tests != nullptr)
    for (std::size_t i = 0; i < top.tests->size(); ++i)
      check_test(c, (*top.tests)[i], i, o.hidden, tallies);

  if (top.score != nullptr && top.tests != nullptr &&
      !close(top.score->get<double>(), tallies.all.score))
    c.fail("results.score = " + top.score->dump() + ", but the tests' scores add up to " +
           std::to_string(tallies.all.score));
  const double total = top.score != nullptr ? top.score->get<double>() : 0.0;
  const std::string text = top.output != nullptr ? top.output->get<std::string>() : "";
  const std::size_t count = top.tests != nullptr ? top.tests->size() : 0;
  check_expected(c, o, tallies, total, count, text);

  if (!c.ok()) {
    c.report();
    return 1;
  }
  const Tally& all = tallies.all;
  std::cout << o.file << ": " << count << " tests, " << total << " of " << all.max_score
            << " points (" << all.passed << " passed, " << all.failed << " failed)\n";
  for (const auto& [task, tally] : tallies.tasks)
    std::cout << "  " << task << ": " << tally.score << " of " << tally.max_score << " points ("
              << tally.passed << " passed, " << tally.failed << " failed)\n";
  return 0;
}
