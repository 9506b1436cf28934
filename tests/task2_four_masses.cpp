// Task 2: the structural springs of a grid (2.1)-(2.2) and the forces of all springs (2.3)-(2.4).
// Every expectation comes from physics or from the theory of the method, computed here.
#include "springlab/task2_four_masses.hpp"
#include "lab_testing.hpp"
#include "mistakes.hpp"
#include "probes.hpp"
#include "spring_lists.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/stability.hpp"
#include "springlab/task1_two_masses.hpp"
#include "springlab/this_implementation.hpp"

#include <array>
#include <cmath>
#include <random>
#include <set>
#include <utility>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

namespace {

// The spring forces of `scene` at (r, v), summed per particle by the code under test.
Vectors summed_forces(const std::vector<Spring>& springs, const Vectors& r, const Vectors& v) {
  Vectors force = Vectors::Zero(2, r.cols());
  accumulate_spring_forces(springs, r, v, force);
  return force;
}

// A grid with random positions and velocities, and every spring with its own random k, b and
// rest length: accumulate_spring_forces must use each spring's own values (2.3).
Scene random_grid(int rows, int cols, bool shear, unsigned seed) {
  Scene scene = build_scene(lab_grid(rows, cols, shear, 0.01, "explicit-euler"), implementation());
  // The grid's springs, from the code under test: with none, every force below would be a sum
  // over nothing, and zero forces would pass for right ones.
  Offsets neighbours{{0, 1}, {1, 0}};
  if (shear) neighbours.insert(neighbours.end(), {{1, 1}, {1, -1}});
  INFO("compared: the springs of a " << rows << "x" << cols << " grid, (2.1)");
  CHECK(scene.springs.size() == expected_pairs(rows, cols, neighbours).size());
  randomise(scene.particles, 0.25, 1.0, seed);
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (Spring& s : scene.springs) {
    s.k *= 0.5 + unit(engine);
    s.b *= 0.5 + unit(engine);
    s.rest_length *= 0.8 + 0.4 * unit(engine);
  }
  return scene;
}

// The summed spring forces (no dampers) as common mistakes in accumulate_spring_forces make them:
// F_pq on one end only, on both ends with the same sign, every rest length taken as 1 m.
std::vector<Suspect<Vectors>> spring_sum_mistakes(const std::vector<Spring>& springs,
                                                  const Vectors& r) {
  const auto sum = [&](double q_sign, double p_sign, bool unit_rest) {
    Vectors f = Vectors::Zero(2, r.cols());
    for (const Spring& s : springs) {
      // (1.1) as task 1's spring_force gives it (the reference's, in a test of task 2)
      const Vec2 f_pq = spring_force(r.col(s.p), r.col(s.q), s.k, unit_rest ? 1.0 : s.rest_length);
      f.col(s.p) += p_sign * f_pq;
      f.col(s.q) += q_sign * f_pq;
    }
    return f;
  };
  return {{"F_pq is added to both ends with the same sign: (2.4) gives q the opposite force, "
           "F_qp = -F_pq",
           sum(1.0, 1.0, false)},
          {"only one end of each spring gets its force: (2.4) adds F_pq to p and -F_pq to q",
           sum(0.0, 1.0, false)},
          {"only one end of each spring gets its force: (2.4) adds F_pq to p and -F_pq to q",
           sum(-1.0, 0.0, false)},
          {"every spring has the rest length 1 m: use each spring's own rest length (2.3)",
           sum(-1.0, 1.0, true)},
          {"the spring forces have the opposite sign (1.1)", sum(1.0, -1.0, false)}};
}

}  // namespace

TEST_CASE("Structural springs: the count, each neighbour pair once, no self-springs",
          "[task2][topology]") {
  const auto [rows, cols] =
      GENERATE(std::pair{1, 2}, std::pair{2, 1}, std::pair{2, 2}, std::pair{3, 3}, std::pair{3, 5},
               std::pair{5, 3}, std::pair{1, 7}, std::pair{4, 6});
  const SpringFamilyParameters family{true, 20.0, 0.1, 1.0};
  const std::vector<Spring> springs = structural_springs(rows, cols, family);
  CAPTURE(rows, cols);
  // When the list differs: what differs, and what it has in common on other grid sizes.
  const Offsets right_and_down = {{0, 1}, {1, 0}};
  const ListReport report =
      compare_list(springs, rows, cols, right_and_down).same()
          ? ListReport{}
          : describe_list([&](int r, int c) { return structural_springs(r, c, family); }, rows,
                          cols, right_and_down, "structural_springs", "(2.2)");
  INFO(report.mistake);
  {
    INFO("equation (2.2): rows*(cols-1) + cols*(rows-1) springs, right and down neighbours");
    const long expected = long(rows) * (cols - 1) + long(cols) * (rows - 1);
    INFO((report.compared.empty() ? "compared: the number of springs structural_springs returns"
                                  : report.compared));
    REQUIRE(long(springs.size()) == expected);
  }
  INFO(
      "equation (2.1): particle [i, j] has the index i*cols + j, from 0 to rows*cols - 1, and "
      "each spring joins neighbours one row or one column apart");
  INFO(report.compared);
  std::set<std::pair<int, int>> pairs;
  for (const Spring& s : springs) {
    CAPTURE(s.p, s.q);
    REQUIRE(std::min(s.p, s.q) >= 0);
    REQUIRE(std::max(s.p, s.q) < rows * cols);
    REQUIRE(s.p != s.q);
    // Index i·cols + j (2.1): neighbours differ by one row or one column, never both.
    const int dr = std::abs(s.p / cols - s.q / cols), dc = std::abs(s.p % cols - s.q % cols);
    CHECK(dr + dc == 1);
    pairs.insert(std::minmax(s.p, s.q));
  }
  CHECK(pairs.size() == springs.size());  // no pair twice, in either order
}

TEST_CASE("Structural springs carry the structural family's values", "[task2][topology]") {
  INFO("equation (2.2); each spring: family structural, k, b and rest length of the family");
  const SpringFamilyParameters family{true, 31.0, 0.7, 1.25};
  for (const Spring& s : structural_springs(3, 4, family)) {
    CAPTURE(s.p, s.q, to_string(s.family), s.k, s.b, s.rest_length);
    INFO(recognise_family(s, SpringFamily::structural, family, "(2.2)"));
    CHECK(carries(s, SpringFamily::structural, family));
  }
}

TEST_CASE("Structural springs join particles one spacing apart: the grid at rest feels no force",
          "[task2][topology][spring]") {
  INFO("equations (2.2), (2.3): at rest every spring has its rest length, so every F_i = 0");
  const Scene scene = build_scene(lab_grid(4, 3, false, 0.01, "explicit-euler"), implementation());
  REQUIRE_FALSE(scene.springs.empty());
  for (const Spring& s : scene.springs)
    CHECK_THAT((scene.particles.position.col(s.p) - scene.particles.position.col(s.q)).norm(),
               WithinAbs(s.rest_length, 1e-12));
  const Vectors f =
      summed_forces(scene.springs, scene.particles.position, scene.particles.velocity);
  // Springs at rest length, but forces: what probing the sum shows.
  INFO((f.norm() > 1e-12
            ? probe_force_sum(force_sum_of(implementation()), spring_force_of(implementation()),
                              damper_force_of(implementation()))
            : std::string()));
  CHECK(f.norm() <= 1e-12);
}

TEST_CASE("Spring forces: the sum is minus the gradient of the total spring energy",
          "[task2][spring]") {
  INFO(
      "equations (2.3), (1.1): F_i = -dE/dr_i with E = sum of 1/2 k (L - l0)^2, by finite "
      "differences");
  Scene scene = random_grid(3, 4, false, 21);
  const Vectors r = scene.particles.position;
  const Vectors still = Vectors::Zero(2, r.cols());
  const Vectors f = summed_forces(scene.springs, r, still);
  const Vectors expected = energy_force(scene.springs, r);
  const std::string known =
      recognise(f, spring_sum_mistakes(scene.springs, r), 1e-6 * (1.0 + expected.norm()));
  INFO((known.empty() && (f - expected).norm() > 1e-6 * (1.0 + expected.norm())
            ? probe_force_sum(force_sum_of(implementation()), spring_force_of(implementation()),
                              damper_force_of(implementation()))
            : known));
  INFO("compared: the summed spring force on particle i, N");
  for (int i = 0; i < r.cols(); ++i) {
    CAPTURE(i);
    CHECK_THAT(Vec2(f.col(i)), IsNear(expected.col(i), 1e-6 * (1.0 + expected.col(i).norm())));
  }
}

TEST_CASE("Damper forces: minus the gradient of the dissipation, so they never add energy",
          "[task2][damper]") {
  INFO("equations (2.3), (1.2): F_i = -dR/dv_i with R = sum of 1/2 b |v_p - v_q|^2; power = -2R");
  const Scene scene = random_grid(3, 4, false, 22);
  const Vectors& r = scene.particles.position;
  const Vectors& v = scene.particles.velocity;
  // The dampers' part: the forces with these velocities minus the forces with none.
  const Vectors f = summed_forces(scene.springs, r, v) -
                    summed_forces(scene.springs, r, Vectors::Zero(2, r.cols()));
  double dissipation = 0.0;  // R
  for (const Spring& s : scene.springs)
    dissipation += 0.5 * s.b * (v.col(s.p) - v.col(s.q)).squaredNorm();
  double power = 0.0;
  for (int i = 0; i < r.cols(); ++i)
    power += f.col(i).dot(v.col(i));
  // Per particle: F_i = -sum over its springs of b (v_i - v_j), from dR/dv_i.
  Vectors expected = Vectors::Zero(2, r.cols());
  for (const Spring& s : scene.springs) {
    expected.col(s.p) -= s.b * (v.col(s.p) - v.col(s.q));
    expected.col(s.q) -= s.b * (v.col(s.q) - v.col(s.p));
  }
  INFO("compared: the dampers' power sum F_i . v_i, W: -2R");
  // A shape is named only when it is every particle's damper force, not the power alone.
  std::vector<Suspect<Vectors>> shapes;
  for (const auto& [words, factor] :
       {std::pair{"the dampers' power has the opposite sign: the damper forces of (1.2) point "
                  "the wrong way",
                  -1.0},
        std::pair{"the dampers' power is zero: no damper force reaches any particle", 0.0},
        std::pair{"the dampers' power is twice what it should be: each damper counted twice, or "
                  "2b",
                  2.0},
        std::pair{"the dampers' power is half what it should be: a factor 2 missing", 0.5}})
    shapes.push_back({words, Vectors(factor * expected)});
  const std::string known = recognise(f, shapes, 1e-9 * (1.0 + expected.norm()));
  INFO((known.empty() && std::abs(power + 2.0 * dissipation) > 1e-12 * dissipation
            ? probe_force_sum(force_sum_of(implementation()), spring_force_of(implementation()),
                              damper_force_of(implementation()))
            : known));
  CHECK(power <= 0.0);
  CHECK_THAT(power, WithinRel(-2.0 * dissipation, 1e-12));
  for (int i = 0; i < r.cols(); ++i) {
    CAPTURE(i);
    CHECK_THAT(Vec2(f.col(i)), IsNear(expected.col(i), 1e-12));
  }
}

TEST_CASE("Spring forces are added to what is already there", "[task2][spring]") {
  INFO("accumulate_spring_forces adds to `force`; it does not clear it (other forces come first)");
  Scene scene = random_grid(2, 2, false, 23);
  const Vectors& r = scene.particles.position;
  const Vectors& v = scene.particles.velocity;
  {
    Vectors force = Vectors::Constant(2, r.cols(), 0.5);
    accumulate_spring_forces(scene.springs, r, v, force);
    const Vectors alone = summed_forces(scene.springs, r, v);
    REQUIRE(alone.norm() > 0.1);
    INFO("compared: how far `force` is from what was there plus the spring forces, N");
    INFO(recognise(
        force, {{"`force` was cleared (set to zero) first: add to what is there", alone}}, 1e-12));
    CHECK((force - alone - Vectors::Constant(2, r.cols(), 0.5)).norm() <= 1e-12);
  }
  {
    // A spring's family only names it: (2.3) uses its own k, b and rest length, so the same
    // springs labelled shear and bend (tasks 3 and 5 hand them over so) give the same forces.
    std::vector<Spring> labelled = scene.springs;
    for (std::size_t i = 0; i < labelled.size(); ++i)
      labelled[i].family = spring_families[i % 3];
    const Vectors as_structural = summed_forces(scene.springs, r, v);
    INFO(
        "compared: the forces of the same springs labelled structural, shear and bend in turn, "
        "against all labelled structural, N");
    CHECK((summed_forces(labelled, r, v) - as_structural).norm() <=
          1e-12 * (1.0 + as_structural.norm()));
  }
  // A 1x1 grid has no springs: nothing is added, and no spring may be read (a loop to
  // springs.size() - 1 in unsigned arithmetic runs past the end of the empty list).
  const std::vector<Spring> none;
  const Vectors at_rest = Vectors::Zero(2, 1);
  Vectors force = Vectors::Constant(2, 1, 0.5);
  accumulate_spring_forces(none, at_rest, at_rest, force);
  INFO("compared: `force` of one particle after accumulate_spring_forces with no springs, N");
  CHECK_THAT(Vec2(force.col(0)), IsNear(Vec2(0.5, 0.5), 0.0));
}

TEST_CASE("Spring forces: internal forces sum to zero, and without dampers their torque too",
          "[task2][momentum]") {
  INFO("equation (2.4): F_qp = -F_pq, so sum F_i = 0; central springs give sum r_i x F_i = 0");
  const unsigned seed = GENERATE(31u, 32u, 33u, 34u);
  Scene scene = random_grid(3, 4, false, seed);
  const Vectors& r = scene.particles.position;
  const Vectors f = summed_forces(scene.springs, r, scene.particles.velocity);
  CAPTURE(seed);
  CHECK_THAT(Vec2(f.rowwise().sum()), IsNear(Vec2::Zero(), 1e-12));
  for (Spring& s : scene.springs)
    s.b = 0.0;
  const Vectors central = summed_forces(scene.springs, r, scene.particles.velocity);
  double torque = 0.0;
  for (int i = 0; i < r.cols(); ++i)
    torque += r(0, i) * central(1, i) - r(1, i) * central(0, i);
  CHECK_THAT(torque, WithinAbs(0.0, 1e-11));
  // Zero sums of forces that are there: each spring's pair of forces has the virial
  // (r_p - r_q) . F_pq = -k (L - l0) L (1.1), so sum r_i . F_i is the sum of those.
  double virial = 0.0, expected = 0.0;
  for (const Spring& s : scene.springs) {
    const double length = (r.col(s.p) - r.col(s.q)).norm();
    expected -= s.k * (length - s.rest_length) * length;
  }
  for (int i = 0; i < r.cols(); ++i)
    virial += r.col(i).dot(central.col(i));
  CHECK_THAT(virial, WithinRel(expected, 1e-9));
}

TEST_CASE("Grid: total momentum is conserved over thousands of steps", "[task2][momentum]") {
  INFO("equation (2.4): no net internal force, so P = sum m_i v_i never changes");
  Scene scene = random_grid(2, 2, false, 41);
  scene.parameters.step = 0.004;  // below explicit Euler's limit for this grid
  // The forces at the start: the springs' -dE/dr_i and the dampers' -sum b (v_i - v_j) (2.3).
  const Vectors r0 = scene.particles.position, v0 = scene.particles.velocity;
  Vectors force = energy_force(scene.springs, r0);
  for (const Spring& s : scene.springs) {
    force.col(s.p) -= s.b * (v0.col(s.p) - v0.col(s.q));
    force.col(s.q) -= s.b * (v0.col(s.q) - v0.col(s.p));
  }
  const double h = scene.parameters.step;
  const Eigen::VectorXd mass = scene.particles.mass;
  Simulation sim(std::move(scene), implementation());
  const Vec2 start = sim.diagnostics().momentum;
  REQUIRE(start.norm() > 0.1);
  sim.step();
  // Conserved because the forces cancel, not because there are none: the first step changed
  // each velocity by h F_i / m_i (1.5).
  for (int i = 0; i < r0.cols(); ++i) {
    CAPTURE(i);
    const Vec2 expected = v0.col(i) + h * force.col(i) / mass(i);
    CHECK_THAT(Vec2(sim.particles().velocity.col(i)),
               IsNear(expected, 1e-6 * h * (1.0 + force.col(i).norm()) / mass(i)));
  }
  const double worst = momentum_drift(sim, 4999);
  CAPTURE(start, worst);
  CHECK(worst <= 1e-12);
}

TEST_CASE("Grid: a mirror-symmetric start moves mirror-symmetrically", "[task2][symmetry]") {
  INFO("equations (2.1)-(2.4): mirroring the grid left-right mirrors its motion");
  const int rows = 3, cols = 4;  // not square, so rows and columns cannot be mixed up unseen
  Scene scene = build_scene(lab_grid(rows, cols, false, 0.004, "explicit-euler"), implementation());
  Vectors& r = scene.particles.position;
  // Move the top corners apart and the bottom-middle pair down, symmetrically about x = 1.5.
  r.col(at(0, 0, cols)) += Vec2(-0.2, 0.15);
  r.col(at(0, 3, cols)) += Vec2(0.2, 0.15);
  r.col(at(2, 1, cols)) += Vec2(0.05, -0.2);
  r.col(at(2, 2, cols)) += Vec2(-0.05, -0.2);
  Simulation sim(std::move(scene), implementation());
  const double axis = 1.5;
  double worst = 0.0;
  run(sim, 2000, [&](const Simulation& s) {
    const Particles& p = s.particles();
    for (int row = 0; row < rows; ++row)
      for (int col = 0; col < cols; ++col) {
        const Vec2 a = p.position.col(at(row, col, cols));
        const Vec2 b = p.position.col(at(row, cols - 1 - col, cols));
        worst = std::max({worst, std::abs(a.x() + b.x() - 2 * axis), std::abs(a.y() - b.y())});
      }
  });
  CAPTURE(worst);
  CHECK(worst <= 1e-10);
  CHECK(sim.diagnostics().kinetic > 0.0);
}

TEST_CASE("Grid: explicit Euler grows at the rate the linear theory predicts",
          "[task2][euler][stability]") {
  INFO("equation (2.5): the largest |1 + h lambda| over the modes lambda of the linearised grid");
  const SceneParameters p = task_scene(2);
  const LinearModel model = linearise_at_rest(p, implementation());
  const double limit = explicit_euler_critical_step(model);
  REQUIRE(limit < p.step);              // the lab step is beyond it
  const int which = GENERATE(0, 1, 2);  // the lab step, just above the limit, just below it
  const double h = std::array{p.step, 1.1 * limit, 0.9 * limit}[std::size_t(which)];
  Scene scene = perturbed_at_rest(p, implementation(), 1e-9, 5);
  scene.parameters.step = h;
  const double predicted = explicit_euler_growth_factor(model, h);
  const double measured =
      measured_growth_factor(std::move(scene), implementation(), h == p.step ? 3000 : 60000);
  CAPTURE(h, limit, predicted, measured);
  CHECK_THAT(measured, WithinAbs(predicted, 0.05 * std::abs(predicted - 1.0)));
  CHECK((measured > 1.0) == (h > limit));
}
