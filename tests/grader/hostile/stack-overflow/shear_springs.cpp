// Attack (or a recursion without end): shear_springs recurses forever with a large frame, so the
// stack overflows within milliseconds. Every task 3 test calls it: each must fail as a crash
// (segmentation fault), not hang or take the grader with it.
#include "springlab/task3_shear_springs.hpp"

using namespace springlab;

namespace {
int deeper(int depth) {
  volatile char frame[4096];
  frame[depth % 4096] = char(depth);
  return deeper(depth + 1) + frame[(depth * 7) % 4096];  // not a tail call
}
}  // namespace

std::vector<Spring> springlab::shear_springs(int rows, int, const SpringFamilyParameters&) {
  return std::vector<Spring>(std::size_t(deeper(rows)));
}
