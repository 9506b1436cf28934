#include "springlab/scene_file.hpp"

#include "springlab/errors.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>

namespace springlab {
namespace {

std::string place(const std::string& path, const toml::source_region& where) {
  return path + ":" + std::to_string(where.begin.line);
}

std::string kind_of(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "a whole number";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "true/false";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date or time";
  }
}

// The value as the file writes it, and what kind of value that is.
std::string as_written(const toml::node& node) {
  std::ostringstream out;
  node.visit([&](const auto& value) { out << value; });
  return out.str() + " (" + kind_of(node) + ")";
}

// The node's value as set_parameter reads it, if its TOML type fits the field's C++ type:
// strings for names, booleans for switches, whole numbers for counts, any number for reals.
template <class T>
bool text_for(const toml::node& node, std::string& text) {
  if constexpr (std::is_same_v<T, std::string>) {
    if (auto s = node.as_string()) return text = s->get(), true;
  } else if constexpr (std::is_same_v<T, bool>) {
    if (auto b = node.as_boolean()) return text = b->get() ? "true" : "false", true;
  } else {
    if (auto i = node.as_integer()) return text = std::to_string(i->get()), true;
    if constexpr (std::is_floating_point_v<T>) {
      if (auto f = node.as_floating_point()) {
        std::ostringstream out;
        out.precision(17);
        out << f->get();
        return text = out.str(), true;
      }
    }
  }
  return false;
}

template <class T>
const char* expected_kind() {
  if constexpr (std::is_same_v<T, std::string>) return "a string in quotes";
  if constexpr (std::is_same_v<T, bool>) return "true or false";
  if constexpr (std::is_integral_v<T>) return "a whole number";
  return "a number";
}

void apply(const std::string& path, const toml::table& table, const std::string& prefix,
           SceneParameters& p) {
  for (const auto& [name, node] : table) {
    const std::string key = prefix + std::string(name.str());
    if (const toml::table* inner = node.as_table()) {
      apply(path, *inner, key + ".", p);
      continue;
    }
    const std::string where = place(path, node.source()) + ": ";
    std::string text;
    bool known = false;
    const char* wanted = nullptr;  // set when the key is known but the TOML type does not fit
    for_each_field(p, [&](const FieldInfo& info, auto& value) {
      using T = std::decay_t<decltype(value)>;
      if (info.key != key) return;
      known = true;
      if (!text_for<T>(node, text)) wanted = expected_kind<T>();
    });
    if (!known)
      throw InvalidParameter(
          where + key, as_written(node),
          "there is no parameter \"" + key + "\"; did you mean \"" + nearest_key(key) + "\"?");
    if (wanted)
      throw InvalidParameter(where + key, as_written(node), std::string("expected ") + wanted);
    try {
      set_parameter(p, key, text);  // also names an unknown key and the nearest known one
    } catch (const InvalidParameter& error) {
      throw InvalidParameter(where + error.field(), error.value(), error.allowed());
    }
  }
}

}  // namespace

SceneParameters load_scene_file(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw InvalidParameter("scene", "\"" + path + "\"",
                           "task1 ... task5 or the path of a readable scene file");
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  if (!file) throw InvalidParameter("scene", "\"" + path + "\"", "a readable scene file");
  return parse_scene(text.str(), path);
}

SceneParameters parse_scene(std::string_view text, const std::string& path) {
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& error) {
    throw InvalidParameter(place(path, error.source()), "(syntax)",
                           std::string(error.description()));
  }
  SceneParameters p;
  p.name = path;
  apply(path, table, "", p);
  try {
    validate(p);  // the checks across fields, e.g. a displaced particle outside the grid
  } catch (const InvalidParameter& error) {
    const toml::node* node = table.at_path(error.field()).node();
    const std::string where = node ? place(path, node->source()) : path;
    throw InvalidParameter(where + ": " + error.field(), error.value(), error.allowed());
  }
  return p;
}

}  // namespace springlab
