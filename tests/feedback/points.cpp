#include "points.hpp"

#include "usage_error.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace springlab::grader {

std::vector<TestInfo> parse_test_list(const std::string& listing) {
  std::vector<TestInfo> tests;
  std::istringstream lines(listing);
  std::string line;
  while (std::getline(lines, line)) {
    const auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    TestInfo test;
    test.name = line.substr(tab + 1);
    std::istringstream tags(line.substr(0, tab));
    std::string tag;
    while (std::getline(tags, tag, ']')) {
      if (tag.empty() || tag.front() != '[') continue;
      test.tags.push_back(tag.substr(1));
      const std::string& t = test.tags.back();
      if (t.size() == 5 && t.rfind("task", 0) == 0 && t[4] >= '1' && t[4] <= '5')
        test.task = t[4] - '0';
      if (t == "hidden") test.hidden = true;
    }
    if (test.task == 0) continue;
    tests.push_back(std::move(test));
  }
  std::stable_sort(tests.begin(), tests.end(), [](const TestInfo& a, const TestInfo& b) {
    return std::pair(a.task, a.hidden) < std::pair(b.task, b.hidden);
  });
  std::map<int, int> counts;
  for (TestInfo& test : tests)
    test.number = ++counts[test.task];
  return tests;
}

std::vector<const TestInfo*> tests_of_task(const std::vector<TestInfo>& tests, int task,
                                           bool with_hidden) {
  std::vector<const TestInfo*> chosen;
  for (const TestInfo& test : tests)
    if (test.task == task && (with_hidden || !test.hidden)) chosen.push_back(&test);
  return chosen;
}

void assign_points(std::vector<TestInfo>& tests, const std::filesystem::path& file) {
  toml::table table;
  try {
    table = toml::parse_file(file.string());
  } catch (const toml::parse_error& error) {
    std::ostringstream where;
    where << file.string() << ":" << error.source().begin.line << ": " << error.description();
    throw UsageError(where.str());
  }
  const auto points_of = [&](const toml::node& node, const std::string& key) {
    const std::optional<double> value = node.value<double>();
    if (!value || !std::isfinite(*value) || *value < 0 || *value > 1e6) {
      std::ostringstream written;
      if (const auto text = node.value<std::string>())
        written << '"' << *text << '"';
      else if (value)
        written << *value;
      else
        written << "a " << node.type();
      throw UsageError(file.string() + ": " + key + " = " + written.str() +
                       ": allowed a number of points from 0 to 1000000");
    }
    return *value;
  };
  for (const auto& [key, node] : table) {
    const std::string task_key(key.str());
    const toml::table* section = node.as_table();
    int task = 0;
    if (task_key.size() == 5 && task_key.rfind("task", 0) == 0) task = task_key[4] - '0';
    if (section == nullptr || task < 1 || task > 5)
      throw UsageError(file.string() + ": [" + task_key +
                       "]: allowed sections are [task1] ... [task5]");
    double fallback = 1.0;
    if (const toml::node* d = section->get("default"))
      fallback = points_of(*d, task_key + ".default");
    double hidden = fallback;  // a hidden test's, unless the section says otherwise
    if (const toml::node* h = section->get("hidden")) hidden = points_of(*h, task_key + ".hidden");
    for (TestInfo& test : tests)
      if (test.task == task) test.points = test.hidden ? hidden : fallback;
    for (const auto& [name_key, value] : *section) {
      const std::string name(name_key.str());
      if (name == "default" || name == "hidden") continue;
      const double points = points_of(value, "[" + task_key + "] \"" + name + "\"");
      bool known = false;
      for (TestInfo& test : tests)
        if (test.task == task && test.name == name) test.points = points, known = true;
      if (!known) {
        std::string names;
        for (const TestInfo& test : tests)
          if (test.task == task) names += "\n  " + test.name;
        throw UsageError(file.string() + ": [" + task_key + "] \"" + name + "\": no test of task " +
                         std::to_string(task) + " has this name; its tests are:" + names);
      }
    }
  }
}

}  // namespace springlab::grader
