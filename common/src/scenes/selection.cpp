#include "springlab/selection.hpp"

#include "springlab/errors.hpp"

#include <algorithm>
#include <charconv>
#include <string>

namespace springlab {
namespace {

const char* const forms =
    "comma-separated items: none, all, top-row, bottom-row, left-column, right-column, "
    "top-corners, corners, an index or a range, e.g. top-corners,14 or 0-9";

bool parse_index(std::string_view text, long& out) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
  return error == std::errc{} && end == text.data() + text.size() && out >= 0;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && text.front() == ' ')
    text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ')
    text.remove_suffix(1);
  return text;
}

// The named sets; false when `name` is none of them.
bool named_set(std::string_view name, int rows, int cols, std::vector<int>& out) {
  const auto add_row = [&](int row) {
    for (int col = 0; col < cols; ++col)
      out.push_back(row * cols + col);
  };
  const auto add_column = [&](int col) {
    for (int row = 0; row < rows; ++row)
      out.push_back(row * cols + col);
  };
  if (name == "none") return true;
  if (name == "all") {
    for (int row = 0; row < rows; ++row)
      add_row(row);
    return true;
  }
  if (name == "top-row") return add_row(0), true;
  if (name == "bottom-row") return add_row(rows - 1), true;
  if (name == "left-column") return add_column(0), true;
  if (name == "right-column") return add_column(cols - 1), true;
  if (name == "top-corners") return out.insert(out.end(), {0, cols - 1}), true;
  if (name == "corners")
    return out.insert(out.end(), {0, cols - 1, (rows - 1) * cols, rows * cols - 1}), true;
  return false;
}

}  // namespace

std::vector<int> select_particles(std::string_view field, std::string_view text, int rows,
                                  int cols) {
  const long count = long(rows) * long(cols);
  const auto reject = [&](const std::string& why) {
    return InvalidParameter(std::string(field), "\"" + std::string(text) + "\"", why);
  };
  std::vector<int> selected;
  for (std::string_view rest = text; !rest.empty();) {
    const auto comma = rest.find(',');
    const std::string_view item = trimmed(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    if (named_set(item, rows, cols, selected)) continue;
    const auto dash = item.find('-');
    long first = 0, last = 0;
    const bool ok = dash == std::string_view::npos
                        ? parse_index(item, first) && parse_index(item, last)
                        : parse_index(item.substr(0, dash), first) &&
                              parse_index(item.substr(dash + 1), last) && first <= last;
    if (!ok) throw reject(forms);
    if (last >= count)
      throw reject("particle indices from 0 to " + std::to_string(count - 1) +
                   " (rows x cols - 1)");
    for (long i = first; i <= last; ++i)
      selected.push_back(int(i));
  }
  std::sort(selected.begin(), selected.end());
  selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  return selected;
}

}  // namespace springlab
