#include "springlab/scene_file.hpp"

#include "springlab/errors.hpp"

#include <toml++/toml.h>

#include <fstream>
#include <sstream>

namespace springlab {
namespace {

std::string place(const std::string& path, const toml::source_region& where) {
  return path + ":" + std::to_string(where.begin.line);
}

// TOML values as the text set_parameter reads; tables and arrays are not scene values.
bool value_text(const toml::node& node, std::string& text) {
  if (auto s = node.as_string()) return text = s->get(), true;
  if (auto b = node.as_boolean()) return text = b->get() ? "true" : "false", true;
  if (auto i = node.as_integer()) return text = std::to_string(i->get()), true;
  if (auto f = node.as_floating_point()) {
    std::ostringstream out;
    out.precision(17);
    out << f->get();
    return text = out.str(), true;
  }
  return false;
}

void apply_table(const std::string& path, const toml::table& table, const std::string& prefix,
                 SceneParameters& p) {
  for (const auto& [name, node] : table) {
    const std::string key = prefix + std::string(name.str());
    if (const toml::table* inner = node.as_table()) {
      apply_table(path, *inner, key + ".", p);
      continue;
    }
    std::string text;
    if (!value_text(node, text))
      throw InvalidParameter(place(path, node.source()) + ": " + key, "an array",
                             "a number, true/false or a string");
    try {
      set_parameter(p, key, text);
    } catch (const InvalidParameter& error) {
      throw InvalidParameter(place(path, node.source()) + ": " + error.field(), error.value(),
                             error.allowed());
    }
  }
}

}  // namespace

SceneParameters load_scene_file(const std::string& path) {
  if (!std::ifstream(path))
    throw InvalidParameter("scene", "\"" + path + "\"",
                           "task1, task2, task3, task4 or the path of a readable scene file");
  toml::table table;
  try {
    table = toml::parse_file(path);
  } catch (const toml::parse_error& error) {
    throw InvalidParameter(place(path, error.source()), "(syntax)",
                           std::string(error.description()));
  }
  SceneParameters p;
  p.name = path;
  apply_table(path, table, "", p);
  return p;
}

}  // namespace springlab
