#include "springlab/parameters.hpp"

#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/selection.hpp"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>
#include <string>
#include <type_traits>

namespace springlab {
namespace {

std::string number(double x) {
  char text[32];
  auto [end, error] = std::to_chars(text, text + sizeof text, x);
  return error == std::errc{} ? std::string(text, end) : std::string("?");
}

std::string with_unit(double x, std::string_view unit) {
  return unit.empty() ? number(x) : number(x) + " " + std::string(unit);
}

// A rough upper bound of what one particle costs with its springs, integrator copies and the
// model's buffers, to refuse grids that cannot fit before allocating them.
constexpr double bytes_per_particle = 1024.0;

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 8.0 * (1ull << 30);
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

template <class T>
void check_range(const FieldInfo& info, const T& value) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    if (!info.range.contains(double(value)))
      throw InvalidParameter(std::string(info.key), with_unit(double(value), info.unit),
                             "allowed " + info.range.describe(info.key, info.unit));
  }
}

bool parse_bool(std::string_view text, bool& out) {
  if (text == "true" || text == "on" || text == "1") return out = true, true;
  if (text == "false" || text == "off" || text == "0") return out = false, true;
  return false;
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

void validate(const SceneParameters& p) {
  for_each_field(p, [](const FieldInfo& info, const auto& value) { check_range(info, value); });
  const double particles = double(p.rows) * double(p.cols);
  if (particles < 2)
    throw InvalidParameter("rows x cols", std::to_string(p.rows) + " x " + std::to_string(p.cols),
                           "a grid needs at least 2 particles (1 x 2 or larger)");
  const double available = physical_memory_bytes() / 2;
  if (particles * bytes_per_particle > available)
    throw InvalidParameter(
        "rows x cols", std::to_string(p.rows) + " x " + std::to_string(p.cols),
        "it needs about " + number(std::round(particles * bytes_per_particle / (1 << 20))) +
            " MiB; at most " + number(std::floor(available / bytes_per_particle)) +
            " particles fit in half of this machine's memory");
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

void set_number(SceneParameters& p, std::string_view key, double value) {
  set_parameter(p, key, number(value));  // to_chars: the shortest text that reads back exactly
}

void set_assignment(SceneParameters& p, std::string_view assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string_view::npos)
    throw InvalidParameter("--set", "\"" + std::string(assignment) + "\"",
                           "KEY=VALUE, e.g. structural.k=40");
  set_parameter(p, assignment.substr(0, equals), assignment.substr(equals + 1));
}

std::string nearest_key(std::string_view key) {
  std::string best;
  int best_distance = 1 << 30;
  SceneParameters probe;
  for_each_field(probe, [&](const FieldInfo& info, auto&) {
    const int d = edit_distance(key, info.key);
    if (d < best_distance) best_distance = d, best = std::string(info.key);
  });
  return best;
}

void set_parameter(SceneParameters& p, std::string_view key, std::string_view text) {
  bool found = false;
  for_each_field(p, [&](const FieldInfo& info, auto& value) {
    if (info.key != key) return;
    found = true;
    using T = std::decay_t<decltype(value)>;
    const std::string shown = "\"" + std::string(text) + "\"";
    if constexpr (std::is_same_v<T, std::string>) {
      value = std::string(text);
    } else if constexpr (std::is_same_v<T, bool>) {
      if (!parse_bool(text, value))
        throw InvalidParameter(std::string(key), shown, "true or false");
    } else {
      double parsed = 0.0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
      if (error != std::errc{} || end != text.data() + text.size())
        throw InvalidParameter(std::string(key), shown,
                               "a number: " + info.range.describe(key, info.unit));
      check_range(info, parsed);
      value = static_cast<T>(parsed);
    }
  });
  if (!found)
    throw InvalidParameter(std::string(key), std::string(text),
                           "there is no parameter \"" + std::string(key) + "\"; did you mean \"" +
                               nearest_key(key) + "\"?");
}

}  // namespace springlab
