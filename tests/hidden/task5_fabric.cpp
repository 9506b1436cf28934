// Task 5, hidden until the due date (tests/hidden/README.md): a one-column fabric (a rope) with
// its own mass, springs and a steady, slanted wind, run until it rests. The public tests never
// let the wind and gravity act together on a grid that must come to rest.
#include "springlab/task5_fabric.hpp"
#include "lab_testing.hpp"
#include "pins_first.hpp"
#include "springlab/this_implementation.hpp"
#include "springlab/wind.hpp"

#include <Eigen/Cholesky>

#include <cmath>

using namespace springlab;
using namespace springlab::testing;

TEST_CASE(
    "A rope hanging in a steady wind comes to rest straight along weight plus drag, each link "
    "stretched by the load below it",
    "[task5][hidden][gravity][wind][pins]") {
  INFO(
      "(5.2), (5.3), (5.5): at rest every free particle feels F = m g + c w, the same for all, so "
      "the rope lines up with F and its links and bend springs hold the load below them: K u = "
      "|F| for the stretches u along the rope, as in handout (5.6)");
  const bool bend = GENERATE(false, true);
  const int rows = 8;
  const double a = 0.5;  // spacing and structural rest length, m
  SceneParameters p = task_scene(5);
  p.rows = rows;
  p.cols = 1;
  p.spacing = a;
  p.mass = 0.3;
  p.structural = {true, 60.0, 0.3, a};
  p.shear.enabled = false;  // a single column has no cells
  p.bend = {bend, 15.0, 0.3, 2.0 * a};
  // Steady (no gusts) and slanted; the drag also damps every motion, so the rope settles.
  p.wind = {true, Vec2(1.0, 0.25), 6.0, 0.4, 0.0, 3.0, 1};
  p.pinned = "top-row";
  p.integrator = "verlet";
  {  // Before any step, with v = 0: the wind adds c w / m to each free particle, (5.3).
    SceneParameters calm = p;
    calm.wind.enabled = false;
    Simulation with(p, implementation()), without(calm, implementation());
    INFO(pins_first(with.particles().pinned));  // "" unless hold_pinned is the cause
    const Vectors& r = with.particles().position;
    const Vectors v = Vectors::Zero(2, r.cols());
    const Vectors windy = with.acceleration(r, v), still = without.acceleration(r, v);
    const WindField wind(p.wind);
    for (int i = 1; i < rows; ++i) {
      const Vec2 w = wind.velocity(0.0, r.col(i));
      const Vec2 added = p.mass * Vec2(windy.col(i) - still.col(i));  // the wind's force, N
      const double c = added.dot(w) / w.squaredNorm();                // the drag it acts with
      CAPTURE(i, w, added, c, p.wind.drag);
      if (std::abs(c - p.wind.drag) > 1e-9 && std::abs(c - WindParameters{}.drag) <= 1e-9)
        UNSCOPED_INFO("the wind's drag is this wind's own c = wind.drag(), equation (5.3): here "
                      << p.wind.drag << " N*s/m, but your force acts as if c were "
                      << WindParameters{}.drag << " N*s/m, the lab's default");
      REQUIRE_THAT(added, IsNear(p.wind.drag * w, 1e-9));
    }
  }
  Simulation sim(p, implementation());
  sim.advance(6000);
  const Vec2 load = p.mass * p.gravity.acceleration +
                    p.wind.drag * p.wind.speed * p.wind.direction.normalized();  // N
  const Vec2 along = load.normalized();
  // The stretches u_1 … u_{rows-1} of the rows below the pinned one along the rope, from the
  // balance of its springs: structural between neighbours, bend two rows apart.
  const int n = rows - 1;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  const auto spring = [&](int top, int bottom, double stiffness) {  // rows; row 0 is pinned
    k(bottom - 1, bottom - 1) += stiffness;
    if (top == 0) return;
    k(top - 1, top - 1) += stiffness;
    k(top - 1, bottom - 1) -= stiffness;
    k(bottom - 1, top - 1) -= stiffness;
  };
  for (int row = 0; row + 1 < rows; ++row)
    spring(row, row + 1, p.structural.k);
  for (int row = 0; bend && row + 2 < rows; ++row)
    spring(row, row + 2, p.bend.k);
  const Eigen::VectorXd stretch = k.ldlt().solve(Eigen::VectorXd::Constant(n, load.norm()));
  CAPTURE(bend, load, sim.diagnostics().kinetic);
  REQUIRE(sim.diagnostics().kinetic < 1e-20);
  for (int row = 1; row < rows; ++row) {
    const Vec2 expected = grid_position(0, 0, a) + (row * a + stretch[row - 1]) * along;
    CAPTURE(row, stretch[row - 1]);
    CHECK_THAT(Vec2(sim.particles().position.col(row)), IsNear(expected, 1e-9));
  }
}
