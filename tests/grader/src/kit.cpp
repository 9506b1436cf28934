#include "kit.hpp"

#include <toml++/toml.h>

#include <stdexcept>

namespace springlab::grader {
namespace {

struct Reader {
  const fs::path& file;

  [[noreturn]] void fail(const std::string& key) const {
    throw std::runtime_error(file.string() + ": '" + key + "' is missing or of the wrong type " +
                             "(the build writes this file: rebuild the kit)");
  }
  std::string text(const toml::node_view<const toml::node>& node, const std::string& key) const {
    if (const auto value = node.value<std::string>()) return *value;
    fail(key);
  }
  std::vector<std::string> texts(const toml::node_view<const toml::node>& node,
                                 const std::string& key) const {
    const toml::array* array = node.as_array();
    if (array == nullptr) fail(key);
    std::vector<std::string> result;
    for (const toml::node& item : *array) {
      const auto value = item.value<std::string>();
      if (!value) fail(key);
      result.push_back(*value);
    }
    return result;
  }
};

Variant variant(const Reader& read, const toml::table& kit, const std::string& name) {
  const auto node = kit[name];
  return {name, read.texts(node["compile"], name + ".compile"),
          read.texts(node["link"], name + ".link"), read.text(node["harness"], name + ".harness"),
          read.texts(node["env"], name + ".env")};
}

}  // namespace

std::string Kit::task_folder(int n) const {
  const std::string& first = task_files.at(n).front();
  return first.substr(0, first.find('/'));
}

Kit read_kit(const fs::path& file) {
  toml::table parsed;
  try {
    parsed = toml::parse_file(file.string());
  } catch (const toml::parse_error& error) {
    throw std::runtime_error(file.string() + ": " + std::string(error.description()));
  }
  const toml::table& kit = parsed;
  const Reader read{file};
  Kit result;
  result.root = read.text(kit["root"], "root");
  result.starter = read.text(kit["starter"], "starter");
  result.solutions = read.text(kit["solutions"], "solutions");
  result.pch = read.text(kit["pch"], "pch");
  result.headers = read.text(kit["headers"], "headers");
  result.points = read.text(kit["points"], "points");
  result.nm = read.text(kit["nm"], "nm");
  for (const std::string& folder : read.texts(kit["system_headers"], "system_headers"))
    result.system_headers.emplace_back(folder);
  for (const std::string& path : read.texts(kit["link_always"], "link_always"))
    result.link_always.emplace_back(path);
  result.plain = variant(read, kit, "plain");
  result.sanitized = variant(read, kit, "sanitized");
  for (int task = 1; task <= 5; ++task) {
    const std::string key = std::to_string(task);
    result.task_files[task] = read.texts(kit["tasks"][key], "tasks." + key);
    result.tables[task] = read.text(kit["tables"][key], "tables." + key);
    if (result.task_files[task].empty()) read.fail("tasks." + key);
  }
  const toml::table* reference = kit["reference"].as_table();
  if (reference == nullptr) read.fail("reference");
  for (const auto& [name, object] : *reference)
    result.reference_objects[std::string(name.str())] = read.text(
        toml::node_view<const toml::node>(object), "reference." + std::string(name.str()));
  return result;
}

}  // namespace springlab::grader
