// Task 3, hidden until the due date (tests/hidden/README.md): shear springs on grids of other
// shapes, with their own spacing and values, sheared cell by cell (the public test shears one
// 2x2 square of the lab's size).
#include "springlab/task3_shear_springs.hpp"
#include "lab_testing.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>
#include <numbers>
#include <utility>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

TEST_CASE(
    "A grid sheared row by row: every cell's two diagonals store k s^2 / 2, the structural "
    "springs next to nothing",
    "[task3][hidden][spring][topology]") {
  INFO(
      "equations (3.1), (3.2): each row slides s further than the one above; in every cell one "
      "diagonal lengthens and the other shortens by s/sqrt(2), each storing 1/2 k (s/sqrt(2))^2");
  const auto [rows, cols] = GENERATE(std::pair{4, 7}, std::pair{7, 4}, std::pair{2, 9});
  const double a = 0.6;  // spacing, m
  SceneParameters p = lab_grid(rows, cols, true, 0.01, "explicit-euler");
  p.spacing = a;
  p.structural = {true, 30.0, 0.2, a};
  p.shear = {true, 12.0, 0.15, std::numbers::sqrt2 * a};  // the diagonal of an a×a cell
  Scene scene = build_scene(p, implementation());
  const double s = 1e-4;  // m; small, so every length changes to first order in s
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col)
      scene.particles.position(0, at(row, col, cols)) += row * s;
  double structural = 0.0, shear = 0.0;
  int diagonals = 0;
  for (const Spring& spring : scene.springs) {
    const bool is_shear = spring.family == SpringFamily::shear;
    (is_shear ? shear : structural) += spring_energy({spring}, scene.particles.position);
    diagonals += is_shear;
  }
  const int cells = (rows - 1) * (cols - 1);
  CAPTURE(rows, cols, cells, diagonals, structural, shear);
  REQUIRE(diagonals == 2 * cells);
  // The diagonals' second-order terms cancel in pairs: the relative error is O((s/a)^2).
  CHECK_THAT(shear, WithinRel(cells * 0.5 * p.shear.k * s * s, 1e-6));
  // Sliding rows keep the row links' lengths; a column link grows by s^2 / (2a) only.
  CHECK_THAT(structural, WithinAbs(0.0, 1e-6 * shear));
}
