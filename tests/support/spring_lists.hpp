// Probing a function that lists a grid's springs (structural_springs, shear_springs,
// bend_springs) when it differs from its equation: which pairs it joins that it should not, which
// it leaves out, which twice, on several grid sizes, described by what they have in common (a
// direction, a row or column, a wrap from one row to the next) and by how their count grows with
// rows and cols. Every finding is a fact measured on the sizes tried, never a guess from a list of
// known mistakes; a mistake is named only when the facts describe it exactly.
#pragma once

#include "springlab/types.hpp"

#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace springlab::testing {

/// A family's springs as offsets: particle [i, j] joined to [i + di, j + dj] (structural:
/// {0, 1} and {1, 0}; shear: {1, 1} and {1, -1}; bend: {0, 2} and {2, 0}).
using Offsets = std::vector<std::pair<int, int>>;

/// The pairs (p < q) the offsets give on a rows × cols grid, index i·cols + j (2.1).
std::set<std::pair<int, int>> expected_pairs(int rows, int cols, const Offsets& offsets);

/// The springs a function returns for a rows × cols grid.
using SpringList = std::function<std::vector<Spring>(int rows, int cols)>;

/// What a spring list is, compared with the expected pairs on one grid.
struct ListDifference {
  int rows = 0, cols = 0;
  long springs = 0;   ///< how many springs the function returned
  long distinct = 0;  ///< distinct pairs among them, either order, inside the grid
  long expected = 0;  ///< pairs the equation gives
  std::vector<std::pair<int, int>> missing, extra, doubled, outside, self;
  bool same() const;
};

ListDifference compare_list(const std::vector<Spring>& got, int rows, int cols,
                            const Offsets& offsets);

/// What a test says of a spring list that differs on rows × cols, as INFO lines for the grader's
/// reporter: `compared` ("compared: ...": what was counted, then a few missing and extra pairs
/// by [row, col]) and `mistake` ("likely mistake: ...": probed on several grid sizes, what the
/// differences have in common and how their count grows). Both "" when the list is right.
struct ListReport {
  std::string compared, mistake;
};
ListReport describe_list(const SpringList& make, int rows, int cols, const Offsets& offsets,
                         const std::string& name, const std::string& equation);

}  // namespace springlab::testing
