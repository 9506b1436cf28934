// The reference model's fast path (grid_forces.hpp) against the plain one (the solutions'
// accumulate_spring_forces, add_gravity and hold_pinned): equal up to rounding on every scene,
// the same bits whatever the number of threads, and only where the springs are whole families.
#include "lab_testing.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/parallel.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>
#include <limits>

using namespace springlab;
using namespace springlab::testing;

namespace {

// The scenes compared: the five built-in ones, and variants that take every branch of the fast
// path: a grid with more columns than rows and one with more rows, each family alone, gravity
// without wind (the fast path then divides by the masses itself), pins, and a grid large enough
// to be split over threads.
std::vector<std::pair<std::string, SceneParameters>> scenes() {
  std::vector<std::pair<std::string, SceneParameters>> out;
  for (int task = 1; task <= 5; ++task)
    out.emplace_back("task" + std::to_string(task), task_scene(task));
  SceneParameters p = task_scene(5);
  p.wind.enabled = false;
  p.rows = 7;
  p.cols = 13;
  out.emplace_back("7x13 fabric, gravity and pins, no wind", p);
  p.rows = 13;
  p.cols = 3;
  out.emplace_back("13x3 fabric", p);
  for (const SpringFamily family : spring_families) {
    SceneParameters alone = p;
    alone.structural.enabled = family == SpringFamily::structural;
    alone.shear.enabled = family == SpringFamily::shear;
    alone.bend.enabled = family == SpringFamily::bend;
    out.emplace_back(std::string(to_string(family)) + " springs alone", alone);
  }
  p.rows = 61;
  p.cols = 59;
  p.wind.enabled = true;
  out.emplace_back("61x59 fabric with wind (split over threads)", p);
  p.push = Vec2(3.0, 1.0);
  p.push_duration = 1.0;
  p.pushed = "bottom-row";
  out.emplace_back("61x59 fabric with wind and a push", p);
  return out;
}

// The scale of the rounding in particle i's force: the sum of the magnitudes of every term
// added into it (each spring's and damper's force, gravity's m g). Two sums of the same terms in
// another order differ by at most about (terms · ε) times this.
Eigen::VectorXd force_scale(const Simulation& s) {
  const Particles& particles = s.particles();
  const Implementation& impl = implementation();
  Eigen::VectorXd scale = Eigen::VectorXd::Zero(particles.size());
  for (const Spring& spring : s.scene().springs) {
    const Vec2 f =
        impl.spring_force(particles.position.col(spring.p), particles.position.col(spring.q),
                          spring.k, spring.rest_length) +
        impl.damper_force(particles.velocity.col(spring.p), particles.velocity.col(spring.q),
                          spring.b);
    scale[spring.p] += f.norm();
    scale[spring.q] += f.norm();
  }
  const SceneParameters& p = s.parameters();
  if (p.gravity.enabled) scale += particles.mass * p.gravity.acceleration.norm();
  return scale;
}

}  // namespace

TEST_CASE("Fast path: every scene's acceleration equals the plain path's up to rounding",
          "[fast]") {
  const int threads_before = thread_count();
  set_thread_count(2);  // the large scenes are split whatever the machine
  for (const auto& [name, p] : scenes()) {
    INFO("scene: " << name);
    Simulation simulation(p, implementation());
    REQUIRE(simulation.fast_forces());
    Particles state = simulation.particles();
    randomise(state, 0.3 * p.spacing, 2.0, 7);
    for (int i = 0; i < state.size(); ++i)
      simulation.set_particle(i, state.position.col(i), state.velocity.col(i));
    const Vectors fast = simulation.acceleration(state.position, state.velocity);
    simulation.set_fast_forces(false);
    REQUIRE_FALSE(simulation.fast_forces());
    const Vectors plain = simulation.acceleration(state.position, state.velocity);
    simulation.set_fast_forces(true);
    // Stated agreement: |a_fast − a_plain| ≤ 16 ε · (Σ |terms|) / m per particle; a particle
    // has at most 12 springs and gravity, so this is a rounding bound, not a tolerance for error.
    const Eigen::VectorXd scale = force_scale(simulation);
    const double eps = std::numeric_limits<double>::epsilon();
    int worst = 0;
    double worst_ratio = 0.0;
    for (int i = 0; i < state.size(); ++i) {
      const double bound = 16 * eps * scale[i] / state.mass[i];
      const double gap = (fast.col(i) - plain.col(i)).norm();
      if (bound > 0 && gap / bound > worst_ratio) {
        worst_ratio = gap / bound;
        worst = i;
      }
      if (bound == 0) CHECK(gap == 0.0);
    }
    INFO("particle " << worst << ": fast " << Vec2(fast.col(worst)).transpose() << ", plain "
                     << Vec2(plain.col(worst)).transpose());
    CHECK(worst_ratio <= 1.0);
    // Not all zero: the comparison compares something.
    CHECK(plain.norm() > 0.0);
  }
  set_thread_count(threads_before);
}

TEST_CASE("Fast path: the same bits whatever the number of threads", "[fast]") {
  REQUIRE(parallel_built());  // the kit is built with OpenMP (Debian's GCC)
  SceneParameters p = task_scene(5);
  p.rows = 80;
  p.cols = 70;
  REQUIRE(p.wind.enabled);
  REQUIRE(p.rows * p.cols >= GridForces::parallel_particles);
  Particles state = build_scene(p, implementation()).particles;
  randomise(state, 0.3 * p.spacing, 2.0, 11);
  // A new simulation for each count: the wind's memory of w must be computed on that many
  // threads too, not read from an earlier evaluation.
  const auto acceleration_on = [&](int threads) {
    set_thread_count(threads);
    Simulation simulation(p, implementation());
    REQUIRE(simulation.fast_forces());
    return Vectors(simulation.acceleration(state.position, state.velocity));
  };
  const int threads_before = thread_count();
  const Vectors one = acceleration_on(1);
  for (const int threads : {2, 3, 7}) {
    INFO(threads << " threads");
    CHECK((acceleration_on(threads).array() == one.array()).all());
  }
  set_thread_count(threads_before);
}

TEST_CASE("Fast path: a run on it follows the plain run", "[fast]") {
  SceneParameters p = task_scene(5);
  p.rows = 30;
  p.cols = 30;
  Simulation fast(p, implementation()), plain(p, implementation());
  plain.set_fast_forces(false);
  REQUIRE(fast.fast_forces());
  REQUIRE_FALSE(plain.fast_forces());
  fast.advance(300);
  plain.advance(300);
  // 3 s of a damped, stable fabric: the rounding differences of each evaluation (~1e-15 of the
  // forces) stay far below a micrometre.
  const double gap = (fast.particles().position - plain.particles().position).cwiseAbs().maxCoeff();
  CHECK(gap < 1e-6);
  CHECK(fast.force_evaluations() == plain.force_evaluations());
}

TEST_CASE("Fast path: only for whole regular families of the kit's own model", "[fast]") {
  const SceneParameters p = task_scene(5);
  const Scene scene = build_scene(p, implementation());
  REQUIRE(GridForces::of(scene.springs, p.rows, p.cols).has_value());
  CHECK(GridForces::of(scene.springs, p.rows, p.cols)->links().size() == 6);

  using Change = void (*)(std::vector<Spring>&, const SceneParameters&);
  const std::pair<const char*, Change> irregular[] = {
      {"a spring missing", [](auto& s, auto&) { s.pop_back(); }},
      {"a spring twice", [](auto& s, auto&) { s.push_back(s.front()); }},
      {"a spring with its own stiffness", [](auto& s, auto&) { s[5].k *= 1.5; }},
      {"a spring with its own damper", [](auto& s, auto&) { s[5].b = 0.0; }},
      {"a spring with its own rest length", [](auto& s, auto&) { s[5].rest_length *= 2; }},
      {"a spring across the grid's edge",
       [](auto& s, const SceneParameters& grid) { s[0].q = s[0].p + grid.cols - 1; }},
      {"a spring to a particle outside the grid",
       [](auto& s, const SceneParameters& grid) { s[0].q = grid.rows * grid.cols; }},
  };
  for (const auto& [what, change] : irregular) {
    INFO(what);
    std::vector<Spring> springs = scene.springs;
    change(springs, p);
    CHECK_FALSE(GridForces::of(springs, p.rows, p.cols).has_value());
  }
  std::vector<Spring> swapped = scene.springs;
  std::swap(swapped[3].p, swapped[3].q);
  CHECK(GridForces::of(swapped, p.rows, p.cols).has_value());  // the same spring

  // Code not the solutions' own table never takes it: it would replace those functions with the
  // kit's. A copy of the table with one function replaced (a test's deliberate mistake) is such.
  REQUIRE(is_kit_model(implementation()));
  const Implementation copy = implementation();
  CHECK_FALSE(is_kit_model(copy));
  CHECK_FALSE(Simulation(p, copy).fast_forces());
  CHECK(Simulation(p, implementation()).fast_forces());
}
