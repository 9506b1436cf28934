#include "springlab/parameters.hpp"

#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/memory_budget.hpp"
#include "springlab/real_text.hpp"
#include "springlab/scene_text.hpp"
#include "springlab/selection.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <string>
#include <type_traits>

namespace springlab {
namespace {

std::string number(double x) {
  return shortest_text(x);
}

std::string unit_after(std::string text, std::string_view unit) {
  return unit.empty() ? text : text + " " + std::string(unit);
}

std::string with_unit(double x, std::string_view unit) {
  return unit_after(number(x), unit);
}

int edit_distance(std::string_view a, std::string_view b) {
  std::vector<int> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = int(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// `written` is the value as the user wrote it, quoted in the message instead of a re-printed
// double (which would show 9223372036854775807 as 9223372036854775808).
template <class T>
void check_range(const FieldInfo& info, const T& value, std::string_view written) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    if (!info.range.contains(double(value)))
      throw InvalidParameter(std::string(info.key), unit_after(std::string(written), info.unit),
                             "allowed " + info.range.describe(info.key, info.unit));
  }
}

template <class T>
void check_range(const FieldInfo& info, const T& value) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>)
    check_range(info, value, number(double(value)));
}

bool parse_bool(std::string_view text, bool& out) {
  if (text == "true" || text == "on" || text == "1") return out = true, true;
  if (text == "false" || text == "off" || text == "0") return out = false, true;
  return false;
}

// The keys of the table `name` ("shear"), e.g. "shear.enabled, shear.k, shear.b".
std::string keys_in(std::string_view name) {
  const SceneParameters probe;
  std::string list;
  for_each_field(probe, [&](const FieldInfo& info, auto&) {
    if (info.key.substr(0, name.size() + 1) == std::string(name) + ".")
      list += (list.empty() ? "" : ", ") + std::string(info.key);
  });
  return list;
}

// The plain keys and the tables, e.g. "name, task, rows, ... and structural.*, shear.*, ...".
std::string overview() {
  const SceneParameters probe;
  std::string keys, tables;
  for_each_field(probe, [&](const FieldInfo& info, auto&) {
    const auto dot = info.key.find('.');
    if (dot == std::string_view::npos) {
      keys += (keys.empty() ? "" : ", ") + std::string(info.key);
      return;
    }
    const std::string table = std::string(info.key.substr(0, dot)) + ".*";
    if (tables.find(table) == std::string::npos) tables += (tables.empty() ? "" : ", ") + table;
  });
  return keys + " and " + tables;
}

// Parses a whole number or a real as from_chars does (no '+', no spaces, nothing after it);
// NaN and infinities come back as parsed, for the range check to refuse them as written.
// Returns "" when it is a number, else what is wrong with the text.
std::string parse_number(std::string_view text, double& out) {
  const RealText real = parse_real(text);
  if (real.error == std::errc::invalid_argument) return "not a number";
  if (real.error == std::errc::result_out_of_range) return "beyond the range of a double";
  out = real.value;
  return "";
}

// One field from text. Messages show the value as `written`, in quotes if `quote` (--set's
// text; a scene file's own text shows its quotes itself).
template <class T>
void set_field(const FieldInfo& info, T& value, std::string_view text, std::string_view written,
               bool quote) {
  const std::string key(info.key);
  const std::string shown = quote ? quoted_for_terminal(written) : std::string(written);
  if constexpr (std::is_same_v<T, std::string>) {
    if (text.empty())
      throw InvalidParameter(key, shown, "an empty text; expected " + std::string(info.meaning));
    // A terminal obeys control characters (ESC starts a command): never store or print them.
    if (has_control_character(text))
      throw InvalidParameter(key, shown,
                             "control characters (such as ESC or a line end) are not allowed");
    if (!is_utf8(text)) throw InvalidParameter(key, printable(shown), "text in UTF-8");
    if (text.size() > max_text_bytes)
      throw InvalidParameter(key, "(" + std::to_string(text.size()) + " bytes of text)",
                             "at most " + std::to_string(max_text_bytes) + " bytes");
    value = std::string(text);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!parse_bool(text, value)) throw InvalidParameter(key, shown, "true or false");
  } else {
    double parsed = 0.0;
    if (const std::string wrong = parse_number(text, parsed); !wrong.empty())
      throw InvalidParameter(key, shown,
                             wrong + "; allowed " + info.range.describe(info.key, info.unit));
    check_range(info, parsed, written);  // a number as written, e.g. -3 N/m
    value = static_cast<T>(parsed);
  }
}

void set_parameter_shown(SceneParameters& p, std::string_view key, std::string_view text,
                         std::string_view written, bool quote) {
  bool found = false;
  for_each_field(p, [&](const FieldInfo& info, auto& value) {
    if (info.key != key) return;
    found = true;
    set_field(info, value, text, written, quote);
  });
  // A key of a pasted page is shown by its start and length, as values are.
  if (!found)
    throw InvalidParameter(key.size() > 120 ? quoted_for_terminal(key) : printable(key),
                           quote ? quoted_for_terminal(written) : std::string(written),
                           unknown_key(key));
}

}  // namespace

bool Range::contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (integer && value != std::floor(value)) return false;
  const bool above = min_open ? value > min : value >= min;
  const bool below = max_open ? value < max : value <= max;
  return above && below;
}

std::string Range::describe(std::string_view key, std::string_view unit) const {
  std::string text = number(min) + (min_open ? " < " : " <= ") + std::string(key) +
                     (max_open ? " < " : " <= ") + with_unit(max, unit);
  if (integer) text += " (a whole number)";
  return text;
}

namespace {

void validate_fields(const SceneParameters& p, bool guard_memory) {
  for_each_field(p, [](const FieldInfo& info, const auto& value) { check_range(info, value); });
  const double particles = double(p.rows) * double(p.cols);
  if (particles < 2)
    throw InvalidParameter("rows x cols", std::to_string(p.rows) + " x " + std::to_string(p.cols),
                           "a grid needs at least 2 particles (1 x 2 or larger)");
  // Before anything of the grid is allocated (select_particles lists particles, too).
  if (guard_memory) check_memory(p, available_memory());
  select_particles("pinned", p.pinned, p.rows, p.cols);
  select_particles("displaced", p.displaced, p.rows, p.cols);
  select_particles("pushed", p.pushed, p.rows, p.cols);
  if (p.wind.enabled && p.wind.direction.isZero())
    throw InvalidParameter("wind.direction", "(0, 0)", "a direction: x and y not both zero");
  if (p.duration / p.step > max_steps)
    throw InvalidParameter("duration / step", number(p.duration) + " s / " + number(p.step) + " s",
                           "at most " + number(max_steps) + " steps in one run");
  if (!is_integrator_name(p.integrator))
    throw InvalidParameter("integrator", "\"" + p.integrator + "\"", integrator_choices());
}

}  // namespace

void validate(const SceneParameters& p) {
  validate_fields(p, true);
}

void validate_built(const SceneParameters& p) {
  validate_fields(p, false);
}

void set_number(SceneParameters& p, std::string_view key, double value) {
  set_parameter(p, key, number(value));  // to_chars: the shortest text that reads back exactly
}

void set_assignment(SceneParameters& p, std::string_view assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string_view::npos)
    throw InvalidParameter("--set", quoted_for_terminal(assignment),
                           "KEY=VALUE, e.g. structural.k=40");
  set_parameter(p, assignment.substr(0, equals), assignment.substr(equals + 1));
}

std::string nearest_key(std::string_view key) {
  // A typo changes a few letters; beyond a third of the key the guess would only mislead.
  const int allowed = std::max(1, int(key.size()) / 3);
  std::string best;
  int best_distance = allowed + 1;
  SceneParameters probe;
  for_each_field(probe, [&](const FieldInfo& info, auto&) {
    // The distance is at least the difference in length: a long text is not compared letter by
    // letter with every key (a pasted line, or a fuzzer's input).
    if (std::abs(int(key.size()) - int(info.key.size())) > allowed) return;
    const int d = edit_distance(key, info.key);
    if (d < best_distance) best_distance = d, best = std::string(info.key);
  });
  return best;
}

bool is_parameter_table(std::string_view name) {
  const SceneParameters probe;
  bool found = false;
  for_each_field(probe, [&](const FieldInfo& info, auto&) {
    found = found || (info.key.size() > name.size() && info.key.substr(0, name.size()) == name &&
                      info.key[name.size()] == '.');
  });
  return found;
}

std::string unknown_key(std::string_view key) {
  const std::string start = "there is no parameter " + quoted_for_terminal(key) + "; ";
  if (const std::string near = nearest_key(key); !near.empty())
    return start + "did you mean \"" + near + "\"?";
  const auto dot = key.rfind('.');
  if (dot != std::string_view::npos && is_parameter_table(key.substr(0, dot)))
    return start + std::string(key.substr(0, dot)) + " has " + keys_in(key.substr(0, dot));
  return start + "the parameters are " + overview() + " (springlab-run --help lists them all)";
}

void set_parameter(SceneParameters& p, std::string_view key, std::string_view text) {
  set_parameter_shown(p, key, text, printable(text), true);
}

void set_parameter(SceneParameters& p, std::string_view key, std::string_view text,
                   std::string_view written) {
  set_parameter_shown(p, key, text, written, false);
}

}  // namespace springlab
