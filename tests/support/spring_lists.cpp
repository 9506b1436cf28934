#include "spring_lists.hpp"
#include "least_squares.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

namespace springlab::testing {
namespace {

using Pair = std::pair<int, int>;

// Grids the probes try besides the test's own: rows and columns apart, both orders, none square.
const std::vector<Pair> probe_sizes = {{2, 3}, {3, 2}, {3, 4}, {4, 3}, {3, 5}, {5, 4}};

std::string where(int index, int cols) {
  return "[" + std::to_string(index / cols) + ", " + std::to_string(index % cols) + "]";
}

std::string pair_text(const Pair& pair, int cols) {
  return where(pair.first, cols) + "-" + where(pair.second, cols);
}

std::string pairs_text(const std::vector<Pair>& pairs, int cols, std::size_t shown = 4) {
  std::string text;
  for (std::size_t i = 0; i < std::min(shown, pairs.size()); ++i)
    text += (i == 0 ? "" : ", ") + pair_text(pairs[i], cols);
  if (pairs.size() > shown) text += ", ... (" + std::to_string(pairs.size()) + " in all)";
  return text;
}

std::string direction_name(const Pair& offset) {
  const auto [di, dj] = offset;
  if (di == 0 && dj == 1) return "to the right neighbour";
  if (di == 1 && dj == 0) return "to the neighbour below";
  if (di == 1 && dj == 1) return "along the down-right diagonal";
  if (di == 1 && dj == -1) return "along the down-left diagonal";
  if (di == 0 && dj == 2) return "two to the right";
  if (di == 2 && dj == 0) return "two below";
  return "with the offset (" + std::to_string(di) + ", " + std::to_string(dj) + ")";
}

// The offset of an expected pair p < q: q's row and column minus p's.
Pair offset_of(const Pair& pair, int cols) {
  return {pair.second / cols - pair.first / cols, pair.second % cols - pair.first % cols};
}

// Where a pair lies, as a predicate over its rows and columns: what missing pairs may share.
struct Place {
  std::string words;  // completes "... springs <words>"
  std::function<bool(const Pair&, int rows, int cols)> holds;
};

const std::vector<Place>& places() {
  static const std::vector<Place> all = {
      {"everywhere", [](const Pair&, int, int) { return true; }},
      {"that reach the last column",
       [](const Pair& p, int, int cols) {
         return std::max(p.first % cols, p.second % cols) == cols - 1;
       }},
      {"that start in the first column",
       [](const Pair& p, int, int cols) { return std::min(p.first % cols, p.second % cols) == 0; }},
      {"that reach the last row",
       [](const Pair& p, int rows, int cols) { return p.second / cols == rows - 1; }},
      {"in the first row (joining it to the next)",
       [](const Pair& p, int, int cols) { return p.first / cols == 0; }},
      {"below the first row", [](const Pair& p, int, int cols) { return p.first / cols >= 1; }},
      {"that end in the last column of a row (the last of each row)",
       [](const Pair& p, int, int cols) { return p.second % cols == cols - 1; }},
  };
  return all;
}

// The subsets of the family's directions, each one alone first, then all together.
std::vector<std::vector<Pair>> direction_sets(const Offsets& offsets) {
  std::vector<std::vector<Pair>> sets;
  for (const Pair& o : offsets)
    sets.push_back({o});
  if (offsets.size() > 1) sets.push_back(offsets);
  return sets;
}

std::string directions_text(const std::vector<Pair>& directions) {
  std::string text;
  for (std::size_t i = 0; i < directions.size(); ++i)
    text += (i == 0                       ? ""
             : i + 1 == directions.size() ? " and "
                                          : ", ") +
            direction_name(directions[i]);
  return text;
}

// The springs of the family with these directions at this place, on a rows × cols grid.
std::vector<Pair> selected(int rows, int cols, const Offsets& offsets,
                           const std::vector<Pair>& directions, const Place& place) {
  std::vector<Pair> result;
  for (const Pair& pair : expected_pairs(rows, cols, offsets))
    if (std::find(directions.begin(), directions.end(), offset_of(pair, cols)) !=
            directions.end() &&
        place.holds(pair, rows, cols))
      result.push_back(pair);
  return result;
}

// The list a function returns for a grid, or nothing when it throws there.
std::optional<std::vector<Spring>> list_of(const SpringList& make, int rows, int cols) {
  try {
    return make(rows, cols);
  } catch (...) {
    return std::nullopt;
  }
}

// What the missing pairs have in common on every size tried, in words, or "".
std::string missing_in_common(const SpringList& make, const Offsets& offsets,
                              const ListDifference& here) {
  if (here.missing.empty()) return "";
  for (const std::vector<Pair>& directions : direction_sets(offsets))
    for (const Place& place : places()) {
      bool everywhere_same = true;
      for (const auto& [rows, cols] : probe_sizes) {
        const auto got = list_of(make, rows, cols);
        if (!got) return "";
        const ListDifference d = compare_list(*got, rows, cols, offsets);
        std::vector<Pair> want = selected(rows, cols, offsets, directions, place);
        everywhere_same = everywhere_same && d.missing == want && !want.empty();
        if (!everywhere_same) break;
      }
      if (!everywhere_same) continue;
      // A fact: the missing pairs are exactly these on every size (other differences aside).
      std::string words =
          "every spring " + directions_text(directions) + " " +
          (place.words == "everywhere" ? std::string("is missing") : place.words + " is missing") +
          ", on every grid tried (" + std::to_string(probe_sizes.size()) +
          " sizes from 2x3 to 5x4)";
      return words;
    }
  return "";
}

// What the extra pairs are, measured: how many join particles with each [row, col] offset, and
// how many of those lie on one row or across two. Facts only: no cause.
std::string extras_text(const ListDifference& d) {
  if (d.extra.empty()) return "";
  std::map<Pair, long> by_offset;
  for (const Pair& pair : d.extra)
    ++by_offset[offset_of(pair, d.cols)];
  std::ostringstream text;
  text << "they join particles";
  bool first = true;
  for (const auto& [offset, count] : by_offset) {
    const int rows_apart = offset.first;
    text << (first ? " " : ", ") << direction_name(offset) << " (" << count << ", "
         << (rows_apart == 0
                 ? std::string("on one row")
                 : std::to_string(rows_apart) + " row" + (rows_apart == 1 ? "" : "s") + " apart")
         << ")";
    first = false;
  }
  return text.str();
}

// A concrete wrong version of a family's list: its pairs on a grid, and the words that name it.
struct ListMistake {
  std::string words;
  std::function<std::vector<Pair>(int rows, int cols)> pairs;
};

// The pairs (p <= q, in order, repeats kept) a list of springs joins.
std::vector<Pair> sorted_pairs(std::vector<Pair> pairs) {
  for (Pair& pair : pairs)
    if (pair.first > pair.second) std::swap(pair.first, pair.second);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<Pair> pairs_of(const std::vector<Spring>& springs) {
  std::vector<Pair> pairs;
  for (const Spring& s : springs)
    pairs.push_back({s.p, s.q});
  return sorted_pairs(pairs);
}

// The family's loops with another index formula: [i, j] -> index(i, j, rows, cols).
std::vector<Pair> with_index(int rows, int cols, const Offsets& offsets,
                             const std::function<int(int, int, int, int)>& index) {
  std::vector<Pair> pairs;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      for (const auto& [di, dj] : offsets)
        if (i + di >= 0 && i + di < rows && j + dj >= 0 && j + dj < cols)
          pairs.push_back({index(i, j, rows, cols), index(i + di, j + dj, rows, cols)});
  return pairs;
}

std::vector<Pair> all_but(int rows, int cols, const Offsets& offsets, const Pair& changed) {
  Offsets others;
  for (const Pair& o : offsets)
    if (o != changed) others.push_back(o);
  const std::set<Pair> kept = expected_pairs(rows, cols, others);
  return {kept.begin(), kept.end()};
}

// Springs of some directions, at some place, left out, and nothing else.
void add_missing(std::vector<ListMistake>& all, const Offsets& offsets) {
  for (const std::vector<Pair>& directions : direction_sets(offsets))
    for (const Place& place : places()) {
      std::string words =
          "every spring " + directions_text(directions) + " " +
          (place.words == "everywhere" ? std::string("is missing") : place.words + " is missing") +
          ", and no other, on every grid tried";
      const bool one_direction = directions.size() == 1 && offsets.size() == 2;
      if (one_direction && place.words == "everywhere")
        words += std::find(offsets.begin(), offsets.end(), Pair{1, 1}) != offsets.end()
                     ? ": one diagonal per cell"
                     : ": one of the two directions";
      else if (place.words == "that reach the last column" ||
               place.words == "that reach the last row")
        words += ": a loop bound one too small";
      all.push_back({words, [offsets, directions, place](int rows, int cols) {
                       const std::vector<Pair> gone =
                           selected(rows, cols, offsets, directions, place);
                       std::vector<Pair> kept;
                       for (const Pair& pair : expected_pairs(rows, cols, offsets))
                         if (std::find(gone.begin(), gone.end(), pair) == gone.end())
                           kept.push_back(pair);
                       return kept;
                     }});
    }
}

// Springs across a row's end: wrapped around by an index checked without its column, or a
// cell's other diagonal taken from its top-left corner.
void add_wrapped(std::vector<ListMistake>& all, const Offsets& offsets) {
  for (const Pair& o : offsets) {
    const auto [di, dj] = o;
    if (dj == 0) continue;
    // Only the index checked, not the column: past a row's end the index runs into the next
    // row (dj > 0), or before its start into the row before the one meant (dj < 0).
    const std::string column =
        "j " + std::string(dj > 0 ? "+ " : "- ") + std::to_string(std::abs(dj));
    all.push_back(
        {"the springs " + direction_name(o) +
             " are made from every particle with only the index checked against the grid, not "
             "the column " +
             column +
             (dj > 0 ? ": from the end of a row they wrap around to the start of the next row"
                     : ": from the start of a row they wrap back to the end of the row before "
                       "the one meant") +
             "; check that " + column + " stays inside 0..cols-1",
         [offsets, o, di = di, dj = dj](int rows, int cols) {
           std::vector<Pair> pairs = all_but(rows, cols, offsets, o);
           for (int p = 0; p < rows * cols; ++p) {
             const int q = p + di * cols + dj;
             if (q >= 0 && q < rows * cols) pairs.push_back({p, q});
           }
           return pairs;
         }});
    if (dj < 0)
      // The cell's other diagonal taken from its top-left corner.
      all.push_back(
          {"the spring " + direction_name(o) +
               " of each cell starts at its top-left "
               "corner [i, j] (to [i+1, j-1]), where (3.1) joins the cell's other two "
               "corners [i, j+1]-[i+1, j]: at j = 0 it reaches back to the end of the row "
               "above",
           [offsets, o, di = di, dj = dj](int rows, int cols) {
             std::vector<Pair> pairs = all_but(rows, cols, offsets, o);
             for (int i = 0; i + di < rows; ++i)
               for (int j = 0; j + 1 < cols; ++j)
                 pairs.push_back({i * cols + j, (i + di) * cols + j + dj});
             return pairs;
           }});
  }
}

// The index formula (2.1) with rows for cols, or column by column.
void add_wrong_index(std::vector<ListMistake>& all, const Offsets& offsets) {
  all.push_back(
      {"the index is i*rows + j where (2.1) has i*cols + j (the same on square grids "
       "only): check the index formula (2.1)",
       [offsets](int rows, int cols) {
         return with_index(rows, cols, offsets, [](int i, int j, int r, int) { return i * r + j; });
       }});
  all.push_back(
      {"the index is j*rows + i, column by column, where (2.1) has i*cols + j, row by "
       "row: check the index formula (2.1)",
       [offsets](int rows, int cols) {
         return with_index(rows, cols, offsets, [](int i, int j, int r, int) { return j * r + i; });
       }});
}

std::vector<ListMistake> list_mistakes(const Offsets& offsets) {
  std::vector<ListMistake> all;
  all.push_back({"each pair is joined twice (once from each end?): join each pair once",
                 [offsets](int rows, int cols) {
                   const std::set<Pair> once = expected_pairs(rows, cols, offsets);
                   std::vector<Pair> twice(once.begin(), once.end());
                   twice.insert(twice.end(), once.begin(), once.end());
                   return twice;
                 }});
  add_missing(all, offsets);
  add_wrapped(all, offsets);
  add_wrong_index(all, offsets);
  return all;
}

// The first concrete mistake whose list is the function's, pair for pair, on the test's grid and
// on every size tried; "" when none is (or the function throws on some size).
std::string list_mistake_everywhere(const SpringList& make, int rows, int cols,
                                    const Offsets& offsets) {
  std::vector<Pair> sizes = probe_sizes;
  sizes.push_back({rows, cols});
  std::vector<std::vector<Pair>> got;
  for (const auto& [r, c] : sizes) {
    const auto list = list_of(make, r, c);
    if (!list) return "";
    got.push_back(pairs_of(*list));
  }
  for (const ListMistake& m : list_mistakes(offsets)) {
    bool everywhere = true;
    for (std::size_t i = 0; i < sizes.size() && everywhere; ++i)
      everywhere = sorted_pairs(m.pairs(sizes[i].first, sizes[i].second)) == got[i];
    if (everywhere) return m.words;
  }
  return "";
}

// The count's formula in rows r and columns c over the sizes tried, a r c + b r + c' c + d with
// whole coefficients, or "" when no such formula fits.
std::string count_formula(const std::function<double(int, int)>& count) {
  Eigen::MatrixXd a(long(probe_sizes.size()), 4);
  Eigen::VectorXd y(long(probe_sizes.size()));
  for (std::size_t i = 0; i < probe_sizes.size(); ++i) {
    const auto [r, c] = probe_sizes[i];
    a.row(long(i)) << double(r) * c, r, c, 1.0;
    y[long(i)] = count(r, c);
    if (std::isnan(y[long(i)])) return "";
  }
  const Eigen::Vector4d x = least_squares(a, y);
  if ((a * x - y).norm() > 1e-6) return "";
  std::ostringstream text;
  const char* terms[] = {"rc", "r", "c", ""};
  bool first = true;
  for (int i = 0; i < 4; ++i) {
    const long k = std::lround(x[i]);
    if (std::abs(x[i] - double(k)) > 1e-6) return "";
    if (k == 0) continue;
    if (first)
      text << (k < 0 ? "-" : "");
    else
      text << (k < 0 ? " - " : " + ");
    if (std::abs(k) != 1 || terms[i][0] == '\0') text << std::abs(k);
    text << terms[i];
    first = false;
  }
  return first ? "0" : text.str();
}

}  // namespace

std::set<std::pair<int, int>> expected_pairs(int rows, int cols, const Offsets& offsets) {
  std::set<Pair> pairs;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      for (const auto& [di, dj] : offsets) {
        const int i2 = i + di, j2 = j + dj;
        if (i2 < 0 || i2 >= rows || j2 < 0 || j2 >= cols) continue;
        pairs.insert(std::minmax(i * cols + j, i2 * cols + j2));
      }
  return pairs;
}

bool ListDifference::same() const {
  return missing.empty() && extra.empty() && doubled.empty() && outside.empty() && self.empty();
}

ListDifference compare_list(const std::vector<Spring>& got, int rows, int cols,
                            const Offsets& offsets) {
  ListDifference d;
  d.rows = rows;
  d.cols = cols;
  d.springs = long(got.size());
  const std::set<Pair> want = expected_pairs(rows, cols, offsets);
  d.expected = long(want.size());
  std::map<Pair, int> seen;
  for (const Spring& s : got) {
    const Pair pair = std::minmax(s.p, s.q);
    if (pair.first < 0 || pair.second >= rows * cols) {
      d.outside.push_back({s.p, s.q});
      continue;
    }
    if (s.p == s.q) {
      d.self.push_back(pair);
      continue;
    }
    if (++seen[pair] == 2) d.doubled.push_back(pair);
  }
  d.distinct = long(seen.size());
  for (const Pair& pair : want)
    if (seen.count(pair) == 0) d.missing.push_back(pair);
  for (const auto& [pair, count] : seen)
    if (want.count(pair) == 0) d.extra.push_back(pair);
  return d;
}

ListReport describe_list(const SpringList& make, int rows, int cols, const Offsets& offsets,
                         const std::string& name, const std::string& equation) {
  const auto here_list = list_of(make, rows, cols);
  if (!here_list) return {};
  // The same grid twice must give the same list: a list kept from call to call (a static vector)
  // grows with each call, and every count below would be of a list the test never saw.
  if (const auto again = list_of(make, rows, cols); again && again->size() != here_list->size()) {
    ListReport report;
    report.compared = "compared: the springs " + name + "(" + std::to_string(rows) + ", " +
                      std::to_string(cols) + ") returns on two calls in a row with that grid";
    report.mistake = "likely mistake: " + name + " returns " + std::to_string(here_list->size()) +
                     " springs, then " + std::to_string(again->size()) +
                     " when called again with the same grid: a list kept from one call to the "
                     "next (a static vector, or one outside the function) keeps what earlier "
                     "calls put in it; build a new list in each call";
    return report;
  }
  const ListDifference d = compare_list(*here_list, rows, cols, offsets);
  if (d.same()) return {};
  std::ostringstream out;
  out << "compared: the springs " << name << "(" << rows << ", " << cols << ") returns, as pairs "
      << "[row, col]-[row, col]: " << d.springs << " spring" << (d.springs == 1 ? "" : "s") << ", "
      << d.distinct << " distinct pair" << (d.distinct == 1 ? "" : "s")
      << " inside the grid, where " << equation << " gives " << d.expected << "\n";
  if (!d.missing.empty()) out << "missing: " << pairs_text(d.missing, cols) << "\n";
  if (!d.extra.empty()) out << "not in " << equation << ": " << pairs_text(d.extra, cols) << "\n";
  if (!d.doubled.empty()) out << "joined more than once: " << pairs_text(d.doubled, cols) << "\n";
  if (!d.outside.empty())
    out << "with an index outside the grid (0 to " << rows * cols - 1 << "): " << d.outside.size()
        << ", e.g. " << d.outside.front().first << "-" << d.outside.front().second << "\n";
  if (!d.self.empty()) out << "joining a particle to itself: " << d.self.size() << "\n";
  ListReport report;
  report.compared = out.str();
  if (!report.compared.empty() && report.compared.back() == '\n') report.compared.pop_back();

  // A concrete wrong list that is the function's on every size tried: named.
  if (const std::string named = list_mistake_everywhere(make, rows, cols, offsets);
      !named.empty()) {
    report.mistake = "likely mistake: " + name + ", " + equation + ": " + named;
    return report;
  }
  // Otherwise what the differences have in common, measured on several sizes: facts, no cause.
  std::vector<std::string> findings;
  if (const std::string missing = missing_in_common(make, offsets, d); !missing.empty())
    findings.push_back(missing);
  if (!d.doubled.empty())
    findings.push_back(std::to_string(d.doubled.size()) + " pair" +
                       (d.doubled.size() == 1 ? " is" : "s are") + " joined more than once here");
  if (const std::string extras = extras_text(d); !extras.empty())
    findings.push_back(std::to_string(d.extra.size()) + " pair" + (d.extra.size() == 1 ? "" : "s") +
                       " not in " + equation + ": " + extras);
  if (!d.outside.empty())
    findings.push_back(
        "some indices are outside the grid: check the index formula (2.1), "
        "i*cols + j, and the loops' bounds (an index out of range)");
  const std::string got_count = count_formula([&](int r, int c) {
    const auto list = list_of(make, r, c);
    return list ? double(compare_list(*list, r, c, offsets).distinct) : std::nan("");
  });
  const std::string want_count =
      count_formula([&](int r, int c) { return double(expected_pairs(r, c, offsets).size()); });
  if (!got_count.empty() && got_count != want_count)
    findings.push_back("on the grids tried (r rows, c columns) the distinct pairs number " +
                       got_count + " where " + equation + " gives " + want_count);
  for (std::size_t i = 0; i < findings.size(); ++i)
    report.mistake +=
        (i == 0 ? "likely mistake: " + name + ", " + equation + ": " : "; ") + findings[i];
  return report;
}

}  // namespace springlab::testing
