// Task 3: the shear springs (3.1), each family with its own values (3.2).
// Every expectation comes from physics or from the theory of the method, computed here.
#include "springlab/task3_shear_springs.hpp"
#include "lab_testing.hpp"
#include "mistakes.hpp"
#include "spring_lists.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/task2_four_masses.hpp"
#include "springlab/this_implementation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <set>
#include <utility>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

namespace {

// Both diagonals of every cell (3.1), as many as the code under test gave `scene`: without them
// the tests of a grid with shear springs would test the structural grid of task 2 again, which a
// shear_springs that returns nothing passes.
void check_shear_springs(const Scene& scene) {
  const int rows = scene.parameters.rows, cols = scene.parameters.cols;
  const auto shear = std::count_if(scene.springs.begin(), scene.springs.end(),
                                   [](const Spring& s) { return s.family == SpringFamily::shear; });
  INFO("compared: the shear springs of the " << rows << "x" << cols << " grid, (3.1)");
  CHECK(std::size_t(shear) == expected_pairs(rows, cols, {{1, 1}, {1, -1}}).size());
}

}  // namespace

TEST_CASE("Shear springs: the count, both diagonals of each cell once, no self-springs",
          "[task3][topology]") {
  INFO("equation (3.1): 2 (rows-1)(cols-1) springs, [i,j]-[i+1,j+1] and [i,j+1]-[i+1,j]");
  const auto [rows, cols] = GENERATE(std::pair{1, 2}, std::pair{2, 2}, std::pair{3, 3},
                                     std::pair{3, 5}, std::pair{5, 3}, std::pair{4, 6});
  const SpringFamilyParameters family{true, 7.0, 0.05, std::numbers::sqrt2};
  const std::vector<Spring> springs = shear_springs(rows, cols, family);
  CAPTURE(rows, cols);
  // When the list differs: what differs, and what it has in common on other grid sizes.
  const Offsets diagonals = {{1, 1}, {1, -1}};
  const ListReport report =
      compare_list(springs, rows, cols, diagonals).same()
          ? ListReport{}
          : describe_list([&](int r, int c) { return shear_springs(r, c, family); }, rows, cols,
                          diagonals, "shear_springs", "(3.1)");
  INFO(report.mistake);
  {
    const long expected = 2L * (rows - 1) * (cols - 1);
    INFO((report.compared.empty() ? "compared: the number of springs shear_springs returns"
                                  : report.compared));
    REQUIRE(long(springs.size()) == expected);
  }
  INFO(report.compared);
  std::set<std::pair<int, int>> pairs;
  std::set<std::pair<int, int>> cells_and_direction;
  for (const Spring& s : springs) {
    CAPTURE(s.p, s.q);
    REQUIRE(s.p != s.q);
    REQUIRE(std::min(s.p, s.q) >= 0);
    REQUIRE(std::max(s.p, s.q) < rows * cols);
    const int dr = s.q / cols - s.p / cols, dc = s.q % cols - s.p % cols;
    CHECK(std::abs(dr) == 1);  // index i·cols + j (2.1): one row and one column apart
    CHECK(std::abs(dc) == 1);
    pairs.insert(std::minmax(s.p, s.q));
    const int top = std::min(s.p / cols, s.q / cols), left = std::min(s.p % cols, s.q % cols);
    cells_and_direction.insert({at(top, left, cols), dr * dc});  // ↘ or ↙ in that cell
  }
  CHECK(pairs.size() == springs.size());
  CHECK(cells_and_direction.size() == springs.size());  // every cell has both diagonals
}

TEST_CASE("Shear springs carry the shear family's own values", "[task3][topology]") {
  INFO("equation (3.2): family shear with the shear k, b and rest length, not the structural ones");
  const SpringFamilyParameters family{true, 7.5, 0.06, 1.5};
  for (const Spring& s : shear_springs(3, 4, family)) {
    CAPTURE(s.p, s.q, to_string(s.family), s.k, s.b, s.rest_length);
    INFO(recognise_family(s, SpringFamily::shear, family, "(3.2)"));
    CHECK(carries(s, SpringFamily::shear, family));
  }
}

TEST_CASE("Shear springs join diagonal neighbours: the lab grid at rest feels no force",
          "[task3][topology][spring]") {
  INFO("equations (3.1), (3.2): a diagonal at rest is sqrt(2) m long, the lab's shear rest length");
  const Scene scene = build_scene(lab_grid(3, 4, true, 0.01, "explicit-euler"), implementation());
  int shear = 0;
  for (const Spring& s : scene.springs) {
    shear += s.family == SpringFamily::shear;
    CHECK_THAT((scene.particles.position.col(s.p) - scene.particles.position.col(s.q)).norm(),
               WithinAbs(s.rest_length, 1e-12));
  }
  CHECK(shear == 2 * 2 * 3);
  Vectors f = Vectors::Zero(2, scene.particles.size());
  accumulate_spring_forces(scene.springs, scene.particles.position, scene.particles.velocity, f);
  CHECK(f.norm() <= 1e-12);
}

TEST_CASE("Grid with shear springs: forces are minus the energy gradient and sum to zero",
          "[task3][spring][momentum]") {
  INFO("equations (2.3), (3.1): F_i = -dE/dr_i over both families; sum F_i = 0");
  Scene scene = build_scene(lab_grid(3, 3, true, 0.01, "explicit-euler"), implementation());
  check_shear_springs(scene);
  randomise(scene.particles, 0.25, 1.0, 51);
  const Vectors r = scene.particles.position;
  const Vectors still = Vectors::Zero(2, r.cols());
  Vectors f = Vectors::Zero(2, r.cols());
  accumulate_spring_forces(scene.springs, r, still, f);
  const Vectors expected = energy_force(scene.springs, r);
  for (int i = 0; i < r.cols(); ++i) {
    CAPTURE(i);
    CHECK_THAT(Vec2(f.col(i)), IsNear(expected.col(i), 1e-6 * (1.0 + expected.col(i).norm())));
  }
  Vectors moving = Vectors::Zero(2, r.cols());
  accumulate_spring_forces(scene.springs, r, scene.particles.velocity, moving);
  CHECK_THAT(Vec2(moving.rowwise().sum()), IsNear(Vec2::Zero(), 1e-12));
}

TEST_CASE("Grid with shear springs: a square no longer shears freely", "[task3][spring]") {
  INFO("without shear springs a 2x2 square can shear at no cost; (3.1) makes shearing cost energy");
  // Shear the square: the bottom row slides right by s. Structural springs barely notice (their
  // stretch is second order in s); the diagonals change length to first order.
  const double s = 1e-3;
  Scene scene = build_scene(lab_grid(2, 2, true, 0.01, "explicit-euler"), implementation());
  scene.particles.position.col(2) += Vec2(s, 0.0);
  scene.particles.position.col(3) += Vec2(s, 0.0);
  double structural = 0.0, shear = 0.0;
  for (const Spring& spring : scene.springs)
    (spring.family == SpringFamily::shear ? shear : structural) +=
        spring_energy({spring}, scene.particles.position);
  // Each diagonal's length changes by about s/sqrt(2): energy 2 · ½ k (s/√2)² = k s² / 2.
  CHECK_THAT(shear, WithinRel(0.5 * scene.parameters.shear.k * s * s, 0.01));
  CHECK(structural < 1e-3 * shear);
}

TEST_CASE("Grid with shear springs: momentum is conserved over thousands of steps",
          "[task3][momentum]") {
  INFO("equation (2.4) over both families: P = sum m_i v_i never changes");
  Scene scene = build_scene(lab_grid(3, 3, true, 0.003, "explicit-euler"), implementation());
  check_shear_springs(scene);
  randomise(scene.particles, 0.2, 0.8, 61);
  Simulation sim(std::move(scene), implementation());
  const Vec2 start = sim.diagnostics().momentum;
  REQUIRE(start.norm() > 0.1);
  const double worst = momentum_drift(sim, 5000);
  CAPTURE(start, worst);
  CHECK(worst <= 1e-12);
}

TEST_CASE("Grid with shear springs: a symmetric start moves symmetrically", "[task3][symmetry]") {
  INFO("mirroring the grid about its diagonal mirrors the motion: [i,j] <-> [j,i]");
  const int n = 3;
  Scene scene = build_scene(lab_grid(n, n, true, 0.003, "explicit-euler"), implementation());
  check_shear_springs(scene);
  // Grid positions (col, -row) mirror about the line y = -x; move particles symmetrically.
  const auto mirror = [](const Vec2& a) { return Vec2(-a.y(), -a.x()); };
  Vectors& r = scene.particles.position;
  r.col(at(2, 2, n)) += Vec2(0.2, -0.2);  // on the diagonal, along it
  r.col(at(0, 1, n)) += Vec2(0.1, 0.15);  // and a pair off it
  r.col(at(1, 0, n)) += mirror(Vec2(0.1, 0.15));
  Simulation sim(std::move(scene), implementation());
  double worst = 0.0;
  run(sim, 3000, [&](const Simulation& s) {
    const Vectors& p = s.particles().position;
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col)
        worst =
            std::max(worst, (Vec2(p.col(at(col, row, n))) - mirror(p.col(at(row, col, n)))).norm());
  });
  CAPTURE(worst);
  CHECK(worst <= 1e-10);
  CHECK(sim.diagnostics().kinetic > 0.0);
}

TEST_CASE("Grid with shear springs: explicit Euler grows at the rate the linear theory predicts",
          "[task3][euler][stability]") {
  INFO("equation (2.5): the largest |1 + h lambda| over the modes lambda of the linearised grid");
  const SceneParameters p = task_scene(3);
  const LinearModel model = linearise_at_rest(p, implementation());
  const double limit = explicit_euler_critical_step(model);
  REQUIRE(limit < p.step);
  const int which = GENERATE(0, 1, 2);  // the lab step, just above the limit, just below it
  const double h = std::array{p.step, 1.1 * limit, 0.9 * limit}[std::size_t(which)];
  Scene scene = perturbed_at_rest(p, implementation(), 1e-9, 6);
  check_shear_springs(scene);
  scene.parameters.step = h;
  const double predicted = explicit_euler_growth_factor(model, h);
  const double measured =
      measured_growth_factor(std::move(scene), implementation(), h == p.step ? 3000 : 60000);
  CAPTURE(h, limit, predicted, measured);
  CHECK_THAT(measured, WithinAbs(predicted, 0.05 * std::abs(predicted - 1.0)));
  CHECK((measured > 1.0) == (h > limit));
}
