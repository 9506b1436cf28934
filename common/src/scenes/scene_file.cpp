#include "springlab/scene_file.hpp"

#include "springlab/errors.hpp"
#include "springlab/scene_text.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

namespace springlab {
namespace {

std::string place(const std::string& path, const toml::source_region& where) {
  return printable(path) + ":" + std::to_string(where.begin.line);
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

// The file's text and name, to quote values as written and to say where they are.
struct Source {
  std::string_view text;
  const std::string& path;
};

// The byte offset of a toml++ position, whose columns count code points from 1.
std::size_t offset_of(std::string_view text, const toml::source_position& at) {
  std::size_t offset = 0;
  for (toml::source_index line = 1; line < at.line && offset < text.size(); ++line) {
    const std::size_t end = text.find('\n', offset);
    offset = end == std::string_view::npos ? text.size() : end + 1;
  }
  for (toml::source_index column = 1; column < at.column && offset < text.size(); ++column) {
    ++offset;
    while (offset < text.size() && (static_cast<unsigned char>(text[offset]) & 0xC0) == 0x80)
      ++offset;  // the rest of a multi-byte character
  }
  return std::min(offset, text.size());
}

// The value as the file writes it (its first line, at most 60 bytes): quoted from the text,
// never re-printed (toml++'s printer shows 0.2 as 0.20000000000000001, 2^63-1 read as a double
// is 9223372036854775808, and the printer's layout code has undefined behaviour on NaN).
std::string written_text(const Source& source, const toml::node& node) {
  if (const toml::table* table = node.as_table(); table && table->empty()) return "{}";
  const std::size_t begin = offset_of(source.text, node.source().begin);
  const std::size_t end = std::max(begin, offset_of(source.text, node.source().end));
  std::string text(source.text.substr(begin, end - begin));
  const std::size_t cut = std::min<std::size_t>(text.find('\n'), 60);
  return cut < text.size() ? text.substr(0, cut) + " ..." : text;
}

// The value as written and what kind of value that is, e.g. "3" (a string).
std::string as_written(const Source& source, const toml::node& node) {
  const toml::table* table = node.as_table();
  return written_text(source, node) + " (" + (table ? "an empty table" : kind_of(node)) + ")";
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

// A key of the file and its value: a value that is not a table, or an empty table.
struct Entry {
  std::string key;
  const toml::node* node;
};

// Every entry, in the order of the file, gathered with a list instead of recursion: nesting
// as deep as the text allows cannot overflow the stack.
std::vector<Entry> entries_of(const toml::table& root) {
  std::vector<Entry> entries;
  std::vector<std::pair<const toml::table*, std::string>> pending{{&root, ""}};
  while (!pending.empty()) {
    const toml::table* table = pending.back().first;
    const std::string prefix = std::move(pending.back().second);
    pending.pop_back();
    for (const auto& [name, node] : *table) {
      std::string key = prefix + std::string(name.str());
      const toml::table* inner = node.as_table();
      if (inner && !inner->empty())
        pending.emplace_back(inner, key + ".");
      else
        entries.push_back({std::move(key), &node});
    }
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    const toml::source_position &x = a.node->source().begin, &y = b.node->source().begin;
    return x.line != y.line ? x.line < y.line : x.column < y.column;
  });
  return entries;
}

void apply(const Source& source, const Entry& entry, SceneParameters& p) {
  const toml::node& node = *entry.node;
  const toml::table* table = node.as_table();
  if (table && is_parameter_table(entry.key)) return;  // e.g. an empty [structural]
  const std::string where = place(source.path, node.source()) + ": " + entry.key;
  std::string text;
  bool known = false;
  const char* wanted = nullptr;  // set when the key is known but the TOML type does not fit
  for_each_field(p, [&](const FieldInfo& info, auto& value) {
    using T = std::decay_t<decltype(value)>;
    if (info.key != entry.key) return;
    known = true;
    if (!text_for<T>(node, text)) wanted = expected_kind<T>();
  });
  if (!known) throw InvalidParameter(where, as_written(source, node), unknown_key(entry.key));
  if (wanted)
    throw InvalidParameter(where, as_written(source, node), std::string("expected ") + wanted);
  try {
    set_parameter(p, entry.key, text, written_text(source, node));
  } catch (const InvalidParameter& error) {
    throw InvalidParameter(where, error.value(), error.allowed());
  }
}

// Whether toml++ failed on a number it cannot hold ("Error while parsing floating-point: ...",
// "... decimal integer: ..."), not on a duplicate key, say.
bool is_number_error(std::string_view description) {
  const std::string_view what = description.substr(0, description.find(':'));
  return what.find("floating-point") != std::string_view::npos ||
         what.find("integer") != std::string_view::npos;
}

// For a syntax error on a line "KEY = VALUE" whose KEY is a numeric parameter (a number beyond a
// double's or an integer's range, say): what KEY allows, which toml++'s own words do not say.
std::string range_hint(std::string_view text, toml::source_index line) {
  std::size_t begin = 0;
  for (toml::source_index n = 1; n < line; ++n) {
    const std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) return "";
    begin = end + 1;
  }
  const std::string_view line_text = text.substr(begin, text.find('\n', begin) - begin);
  const std::size_t equals = line_text.find('=');
  if (equals == std::string_view::npos) return "";
  std::string_view key = line_text.substr(0, equals);
  while (!key.empty() && (key.front() == ' ' || key.front() == '\t'))
    key.remove_prefix(1);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t'))
    key.remove_suffix(1);
  std::string hint;
  const SceneParameters defaults;
  for_each_field(defaults, [&](const FieldInfo& info, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>)
      if (info.key == key) hint = "; allowed " + info.range.describe(info.key, info.unit);
  });
  return hint;
}

}  // namespace

SceneParameters load_scene_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw InvalidParameter("scene", quoted_for_terminal(path),
                           "task1 ... task5, task4-damped or the path of a readable scene file");
  // A scene is a few hundred bytes: a huge file is a mistake, and reading it whole could exhaust
  // the memory before a word is said.
  const auto size = std::filesystem::file_size(path, error);
  if (!error && size > max_scene_file_bytes)
    throw InvalidParameter("scene", quoted_for_terminal(path),
                           "a scene file of at most " + std::to_string(max_scene_file_bytes) +
                               " bytes; this one has " + std::to_string(size));
  // Read with C's calls, whose ferror tells a read that failed midway (a file of /proc, a disk
  // error): a stream says nothing of it and would hand on an empty or cut text as the scene.
  errno = 0;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr)
    throw InvalidParameter("scene", quoted_for_terminal(path),
                           std::string("a readable scene file (") + std::strerror(errno) + ")");
  std::string text;
  char buffer[8192];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, file)) > 0 &&
         text.size() <= max_scene_file_bytes)
    text.append(buffer, got);
  const int reason = errno;
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed)
    throw InvalidParameter("scene", quoted_for_terminal(path),
                           std::string("a readable scene file (") + std::strerror(reason) + ")");
  if (text.size() > max_scene_file_bytes)  // a file that grew, or reports no size (a pipe)
    throw InvalidParameter(
        "scene", quoted_for_terminal(path),
        "a scene file of at most " + std::to_string(max_scene_file_bytes) + " bytes");
  return parse_scene(text, path);
}

SceneParameters parse_scene(std::string_view text, const std::string& path) {
  // A byte-order mark, which some editors write at the start of a UTF-8 file, is no character of
  // the scene.
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  check_scene_text(text, path);  // what toml++ 3.3.0 would mishandle, refused first
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& error) {
    throw InvalidParameter(
        place(path, error.source()), "(syntax)",
        std::string(error.description()) + (is_number_error(error.description())
                                                ? range_hint(text, error.source().begin.line)
                                                : std::string()));
  }
  SceneParameters p;
  p.name = path;
  const Source source{text, path};
  for (const Entry& entry : entries_of(table))
    apply(source, entry, p);
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
