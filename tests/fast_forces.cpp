// The reference model's fast path (grid_forces.hpp) against the plain one (the solutions'
// accumulate_spring_forces, add_gravity and hold_pinned): equal up to rounding on every scene,
// the same bits whatever the number of threads, and only where the springs are whole families.
#include "lab_testing.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/parallel.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>
#include <limits>
#include <optional>

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
  // Task 5 steps with Verlet, whose springs the fast path sums apart from the dampers; other
  // integrators take each spring and damper together.
  REQUIRE(p.integrator == "verlet");
  p.integrator = "symplectic-euler";
  p.push_duration = 0.0;
  out.emplace_back("61x59 fabric with wind, symplectic Euler (springs and dampers together)", p);
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
    simulation.acceleration(state.position, Vectors(0.5 * state.velocity));
    return Vectors(simulation.acceleration(state.position, state.velocity));
  };
  const int threads_before = thread_count();
  const Vectors one = acceleration_on(1);
  REQUIRE(p.integrator == "verlet");  // so a second call at the same r sums only the dampers
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

// GridForces alone, on task 5's springs at 40 x 30 (split over 2 threads) with random positions
// and velocities.
struct GridCase {
  SceneParameters p = [] {
    SceneParameters task5 = task_scene(5);
    task5.rows = 40;
    task5.cols = 30;
    return task5;
  }();
  Scene scene = build_scene(p, implementation());
  GridForces grid = *GridForces::of(scene.springs, p.rows, p.cols);
  Particles state = [this] {
    Particles s = scene.particles;
    randomise(s, 0.3 * p.spacing, 2.0, 5);
    return s;
  }();
};

TEST_CASE("Fast path: Verlet's iterations at the same r sum the springs once", "[fast]") {
  const int threads_before = thread_count();
  set_thread_count(2);
  GridCase c;
  const Vectors& r = c.state.position;
  const Vectors v1 = c.state.velocity, v2 = 0.5 * c.state.velocity;
  GridForces remembering = c.grid;
  remembering.remember_springs(true);
  Vectors f1, f2, fresh, together;
  remembering.compute(r, v1, f1);
  remembering.compute(r, v2, f2);
  // Work counted: the second call, at the same positions, summed the dampers alone.
  CHECK(remembering.spring_passes() == 1);
  CHECK(remembering.damper_passes() == 2);
  // Remembered or not, the same bits: a new GridForces sums both at v2.
  GridForces other = c.grid;
  other.remember_springs(true);
  other.compute(r, v2, fresh);
  CHECK(other.spring_passes() == 1);
  CHECK((f2.array() == fresh.array()).all());
  // Positions that differ in one bit are not the same: the springs are summed again.
  Vectors moved = r;
  moved(1, 17) = std::nextafter(moved(1, 17), 1e300);
  remembering.compute(moved, v2, f1);
  CHECK(remembering.spring_passes() == 2);
  CHECK((f1.array() != f2.array()).any());
  // Apart or together, the same forces up to the rounding of a sum taken in another order.
  c.grid.compute(r, v2, together);
  CHECK(c.grid.spring_passes() == 1);
  CHECK(c.grid.damper_passes() == 0);  // summed with the springs, not apart
  const double eps = std::numeric_limits<double>::epsilon();
  const double largest = together.cwiseAbs().maxCoeff();
  CHECK((fresh - together).cwiseAbs().maxCoeff() <= 64 * eps * largest);
  CHECK(largest > 0.0);
  set_thread_count(threads_before);
}

TEST_CASE("Fast path: the springs' energy equals the plain sum up to rounding", "[fast]") {
  GridCase c;
  const double plain = spring_energy(c.scene.springs, c.state.position);
  const double fast = c.grid.spring_energy(c.state.position);
  REQUIRE(plain > 0.0);
  // Sums of the same positive terms in another order: within (terms · ε) of each other.
  const double eps = std::numeric_limits<double>::epsilon();
  CHECK(std::abs(fast - plain) <= double(c.scene.springs.size()) * eps * plain);
  CHECK(std::abs(fast - plain) <= 1e-12 * plain);
  // A Simulation on the fast path reports it in its diagnostics.
  Simulation simulation(c.p, implementation());
  REQUIRE(simulation.fast_forces());
  CHECK(simulation.diagnostics().potential ==
        c.grid.spring_energy(simulation.particles().position));
}

TEST_CASE("Fast path: the vectorised wind equals w(t, r) to a few units in the last place",
          "[fast]") {
  GridCase c;
  REQUIRE(c.p.wind.enabled);
  c.p.wind.gustiness = 0.9;  // the sines matter
  const WindField wind(c.p.wind);
  const Vectors& r = c.state.position;
  Vectors w(2, r.cols());
  const double eps = std::numeric_limits<double>::epsilon();
  for (const double t : {0.0, 1.37, 250.5}) {
    INFO("t = " << t);
    wind.velocities(t, r.data(), int(r.cols()), w.data());
    double largest_gap = 0.0;
    for (Eigen::Index i = 0; i < r.cols(); ++i)
      largest_gap = std::max(largest_gap, (w.col(i) - wind.velocity(t, r.col(i))).norm());
    // libmvec's sines are within 4 ulp; each of three is scaled by its amplitude (< 1), the
    // gustiness and the speed: 16 ε · speed · (1 + gustiness) is well above that, far below a
    // mistake in the formula.
    CHECK(largest_gap <= 16 * eps * c.p.wind.speed * (1.0 + c.p.wind.gustiness));
    CHECK(w.cwiseAbs().maxCoeff() > 0.0);
  }
}

TEST_CASE("Two threads: the kit's integrators step the same bits on 1, 2 and 3 threads", "[fast]") {
  REQUIRE(parallel_built());
  SceneParameters p = task_scene(5);
  p.rows = 130;  // 17,030 particles: above parallel_items, so the vector work is split too
  p.cols = 131;  // odd: each thread's rows (and its buffers) start at another alignment
  REQUIRE(p.wind.enabled);
  REQUIRE(long(p.rows) * p.cols >= parallel_items);
  const int threads_before = thread_count();
  // Implicit Euler gathers each particle's springs on two threads and scatters each spring to its
  // ends on one: the same additions in the same order.
  for (const char* integrator :
       {"symplectic-euler", "rk4", "velocity-verlet", "verlet", "implicit-euler"}) {
    INFO(integrator);
    p.integrator = integrator;
    const auto run_on = [&](int threads) {
      set_thread_count(threads);
      REQUIRE(splits(long(p.rows) * p.cols) == (threads > 1));
      Simulation simulation(p, implementation());
      simulation.advance(3);
      return simulation.particles();
    };
    const Particles one = run_on(1);
    for (const int threads : {2, 3}) {
      INFO(threads << " threads");
      const Particles many = run_on(threads);
      CHECK((many.position.array() == one.position.array()).all());
      CHECK((many.velocity.array() == one.velocity.array()).all());
    }
    CHECK(one.velocity.cwiseAbs().maxCoeff() > 0.0);  // it moved
  }
  set_thread_count(threads_before);
}

TEST_CASE("Fast path: particles of different masses take the per-particle arrays", "[fast]") {
  SceneParameters p = task_scene(5);
  p.rows = 9;
  p.cols = 8;
  Scene scene = build_scene(p, implementation());
  randomise(scene.particles, 0.3 * p.spacing, 2.0, 3);
  scene.particles.mass[10] *= 3.0;  // no longer one mass for all: gravity and 1/m per particle
  Simulation simulation(std::move(scene), implementation());
  REQUIRE(simulation.fast_forces());
  const Particles& state = simulation.particles();
  const Vectors fast = simulation.acceleration(state.position, state.velocity);
  simulation.set_fast_forces(false);
  const Vectors plain = simulation.acceleration(state.position, state.velocity);
  const Eigen::VectorXd scale = force_scale(simulation);
  const double eps = std::numeric_limits<double>::epsilon();
  for (int i = 0; i < state.size(); ++i) {
    INFO("particle " << i);
    CHECK((fast.col(i) - plain.col(i)).norm() <= 16 * eps * scale[i] / state.mass[i]);
  }
  // The heavier particle falls with g all the same: its own mass is used for both m g and 1/m.
  CHECK(std::abs(fast(1, 10) - plain(1, 10)) <= 1e-12);
  CHECK(plain.col(10).norm() > 0.0);
}

TEST_CASE("Fast path: one mass for all reads no mass array, for forces and accelerations alike",
          "[fast]") {
  SceneParameters p = task_scene(5);
  p.rows = 6;
  p.cols = 7;
  Scene scene = build_scene(p, implementation());
  randomise(scene.particles, 0.3 * p.spacing, 2.0, 5);
  std::optional<GridForces> grid = GridForces::of(scene.springs, p.rows, p.cols);
  REQUIRE(grid);
  const Particles& s = scene.particles;
  const double m = s.mass[0];
  REQUIRE((s.mass.array() == m).all());
  const Vec2 g = p.gravity.acceleration;
  REQUIRE(g.norm() > 0.0);
  // With the arrays: m_i g per particle, then 1/m_i.
  const Eigen::VectorXd inverse = s.mass.cwiseInverse();
  Vectors with_arrays, shared, scratch, a_arrays, a_shared;
  grid->compute(s.position, s.velocity, with_arrays, {.gravity = &g, .mass = &s.mass});
  // same_mass alone: `mass` and `inverse_mass` are left null, and must not be read.
  grid->compute(s.position, s.velocity, shared, {.gravity = &g, .same_mass = m});
  CHECK((shared.array() == with_arrays.array()).all());
  grid->compute(
      s.position, s.velocity, scratch,
      {.gravity = &g, .mass = &s.mass, .inverse_mass = &inverse, .acceleration = &a_arrays});
  grid->compute(
      s.position, s.velocity, scratch,
      {.gravity = &g, .inverse_mass = &inverse, .same_mass = m, .acceleration = &a_shared});
  CHECK((a_shared.array() == a_arrays.array()).all());
  // Not vacuous: gravity is in the result.
  CHECK(with_arrays.row(1).sum() < 0.0);
}

TEST_CASE("Fast path: a row's end in one pass gives the bits of a pass each, as a replay adds them",
          "[fast]") {
  // A replay of a fast-path run (divergence.hpp) takes the forces alone from the fast path, then
  // adds m g, then the wind's drag, then divides by m, a pass each, and must follow the run to
  // the bit. 7 x 9 is finished in one pass over all rows, 61 x 63 row by row through the ring;
  // with remembered springs (Verlet) their sums are added first.
  for (const int rows : {7, 61}) {
    for (const bool remember : {false, true}) {
      INFO(rows << " rows, springs remembered: " << remember);
      SceneParameters p = task_scene(5);
      p.rows = rows;
      p.cols = rows + 2;
      REQUIRE(p.wind.enabled);
      Scene scene = build_scene(p, implementation());
      randomise(scene.particles, 0.3 * p.spacing, 2.0, 11);
      const Particles& s = scene.particles;
      GridForces grid = *GridForces::of(scene.springs, p.rows, p.cols);
      grid.remember_springs(remember);
      const WindField wind(p.wind);
      const double t = 0.37, m = s.mass[0];
      const Vec2 g = p.gravity.acceleration;
      const Eigen::VectorXd inverse = s.mass.cwiseInverse();
      Vectors force, scratch, fused;
      const GridFinish finish{.gravity = &g,
                              .mass = &s.mass,
                              .wind = &wind,
                              .time = t,
                              .inverse_mass = &inverse,
                              .same_mass = m,
                              .acceleration = &fused};
      grid.compute(s.position, s.velocity, scratch, finish);
      if (remember) grid.compute(s.position, s.velocity, scratch, finish);  // springs reused
      grid.compute(s.position, s.velocity, force);
      force += m * g.replicate(1, force.cols());  // (5.2), as add_gravity: f + m g
      grid.add_wind(wind, t, s.position, s.velocity, force);
      const Vectors passes = force * inverse.asDiagonal();
      CHECK((fused.array() == passes.array()).all());
      CHECK(fused.cwiseAbs().maxCoeff() > 0.0);
    }
  }
}
