// Task 2, hidden until the due date (tests/hidden/README.md): grids of other shapes (long, thin,
// a single row or column) with their own spacing, k, b and rest length, deformed so that the
// force on every particle follows from the tension of its links alone.
#include "springlab/task2_four_masses.hpp"
#include "lab_testing.hpp"
#include "springlab/this_implementation.hpp"

#include <utility>

using namespace springlab;
using namespace springlab::testing;

TEST_CASE(
    "A grid stretched along its rows and squeezed along its columns: inner particles feel "
    "nothing, the edges are pulled by the links' tension",
    "[task2][hidden][spring][damper][topology]") {
  INFO(
      "equations (2.2)-(2.4) for any grid shape: stretched evenly, every row link pulls its ends "
      "together with T = k (L - l0) + b dL/dt (1.1)-(1.2), so only the particles at the ends of "
      "a row or column are left with a net force");
  const auto [rows, cols] =
      GENERATE(std::pair{4, 7}, std::pair{7, 4}, std::pair{1, 9}, std::pair{9, 1}, std::pair{2, 6});
  const double a = 0.75;  // spacing = rest length, m
  SceneParameters p = lab_grid(rows, cols, false, 0.01, "explicit-euler");
  p.spacing = a;
  p.structural = {true, 55.0, 0.4, a};
  Scene scene = build_scene(p, implementation());
  // x scaled by sx and y by sy, both changing at the rates ex and ey (1/s): every row link is
  // sx·a long and lengthens at ex·a, every column link sy·a and ey·a.
  const double sx = 1.2, sy = 0.9, ex = 0.5, ey = -0.3;
  Vectors& r = scene.particles.position;
  Vectors& v = scene.particles.velocity;
  for (int i = 0; i < r.cols(); ++i) {
    v.col(i) = Vec2(ex * r(0, i), ey * r(1, i));
    r.col(i) = Vec2(sx * r(0, i), sy * r(1, i));
  }
  const SpringFamilyParameters& s = p.structural;
  const double row_tension = s.k * (sx * a - s.rest_length) + s.b * ex * a;     // N
  const double column_tension = s.k * (sy * a - s.rest_length) + s.b * ey * a;  // N
  Vectors force = Vectors::Zero(2, r.cols());
  accumulate_spring_forces(scene.springs, r, v, force);
  CAPTURE(rows, cols, row_tension, column_tension);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) {
      // A link to the right pulls towards +x, one to the left towards -x; row 0 is on top, so a
      // link below pulls towards -y and one above towards +y.
      const int right = col + 1 < cols, left = col > 0, below = row + 1 < rows, above = row > 0;
      const Vec2 expected(row_tension * (right - left), column_tension * (above - below));
      CAPTURE(row, col);
      CHECK_THAT(Vec2(force.col(at(row, col, cols))), IsNear(expected, 1e-12));
    }
}
