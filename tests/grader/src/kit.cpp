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
          read.texts(node["link"], name + ".link"), read.texts(node["env"], name + ".env")};
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
  result.calibration = read.text(kit["calibration"], "calibration");
  result.pch = read.text(kit["pch"], "pch");
  result.headers = read.text(kit["headers"], "headers");
  result.points = read.text(kit["points"], "points");
  result.nm = read.text(kit["nm"], "nm");
  result.linker_script = read.text(kit["linker_script"], "linker_script");
  for (const std::string& folder : read.texts(kit["system_headers"], "system_headers"))
    result.system_headers.emplace_back(folder);
  result.plain = variant(read, kit, "plain");
  result.sanitized = variant(read, kit, "sanitized");
  for (int task = 1; task <= 5; ++task) {
    const std::string key = std::to_string(task);
    result.task_files[task] = read.texts(kit["tasks"][key], "tasks." + key);
    if (result.task_files[task].empty()) read.fail("tasks." + key);
    const std::vector<std::string> programs = read.texts(kit["programs"][key], "programs." + key);
    if (programs.size() != 2) read.fail("programs." + key);
    result.programs[task] = programs[0];
    result.sanitized_programs[task] = programs[1];
    for (const std::string& part : read.texts(kit["library"][key], "library." + key))
      result.library_parts[task].emplace_back(part);
  }
  return result;
}

}  // namespace springlab::grader
