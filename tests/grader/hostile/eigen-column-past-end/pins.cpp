// Not an attack: a plain mistake that trips one of Eigen's index checks. hold_pinned zeroes the
// column after each pinned particle's, and so asks for a column past the last at the grid's end.
// The feedback must say it in a student's words: the function, its file and line, the sizes it
// was given, and no text of Eigen's (issue 38).
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  for (std::size_t i = 0; i < pinned.size(); ++i)
    if (pinned[i] || i + 1 == pinned.size()) acceleration.col(Eigen::Index(i + 1)).setZero();
}
