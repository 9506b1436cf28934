// The kit's scene machinery (tag [core]): particle sets, the built-in scene files, the wind
// field, the push, and gravity's share of the energy. Students never edit any of it.
#include "lab_testing.hpp"
#include "springlab/builtin_scenes.hpp"
#include "springlab/errors.hpp"
#include "springlab/selection.hpp"
#include "springlab/this_implementation.hpp"
#include "springlab/wind.hpp"

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::Contains;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

TEST_CASE("Particle sets: names, indices, ranges and mixtures", "[core][selection]") {
  using V = std::vector<int>;
  CHECK(select_particles("pinned", "none", 3, 4) == V{});
  CHECK(select_particles("pinned", "top-row", 3, 4) == V{0, 1, 2, 3});
  CHECK(select_particles("pinned", "bottom-row", 3, 4) == V{8, 9, 10, 11});
  CHECK(select_particles("pinned", "left-column", 3, 4) == V{0, 4, 8});
  CHECK(select_particles("pinned", "right-column", 3, 4) == V{3, 7, 11});
  CHECK(select_particles("pinned", "top-corners", 3, 4) == V{0, 3});
  CHECK(select_particles("pinned", "corners", 3, 4) == V{0, 3, 8, 11});
  CHECK(select_particles("pinned", "all", 2, 2) == V{0, 1, 2, 3});
  CHECK(select_particles("pinned", "5, 1-3,top-corners", 3, 4) == V{0, 1, 2, 3, 5});
}

TEST_CASE("Particle sets: bad text names the field, the text and the forms allowed",
          "[core][selection]") {
  const auto message = [](const char* text) {
    return rejection([&] { select_particles("pinned", text, 3, 4); });
  };
  CHECK_THAT(message("12"), Contains("pinned = \"12\"") && Contains("from 0 to 11"));
  CHECK_THAT(message("top"), Contains("pinned = \"top\"") && Contains("top-row"));
  CHECK_THAT(message("3-1"), Contains("pinned = \"3-1\""));
  CHECK_THAT(message("-2"), Contains("pinned = \"-2\""));
  CHECK_THAT(message("1,,2"), Contains("pinned = \"1,,2\""));
  SceneParameters p = task_scene(5);
  CHECK_THAT(rejection([&] { set_parameter(p, "pinned", "400"), validate(p); }),
             Contains("pinned = \"400\"") && Contains("from 0 to 399"));
}

TEST_CASE("Built-in scenes: each task's scene is the TOML file the kit ships", "[core][scene]") {
  REQUIRE(task_scene_names() ==
          std::vector<std::string>{"task1", "task2", "task3", "task4", "task5", "task4-damped"});
  for (const BuiltinScene& builtin : builtin_scenes()) {
    CAPTURE(builtin.path);
    const SceneParameters p = load_scene(std::string(builtin.name));
    CHECK(p.name == builtin.name);
    CHECK(p.task == int(builtin.name[4] - '0'));
    CHECK_NOTHROW(validate(p));
    // The same file read from the source tree gives the same scene.
    const std::filesystem::path file = std::filesystem::path(SPRINGLAB_SOURCE_DIR) / builtin.path;
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    CHECK(text.str() == builtin.text);
  }
  const SceneParameters fabric = task_scene(5);
  CHECK(fabric.rows == 20);
  CHECK(fabric.cols == 20);
  CHECK((fabric.shear.enabled && fabric.bend.enabled && fabric.gravity.enabled));
  CHECK(fabric.bend.rest_length == 2.0);
  CHECK_THAT(rejection([] { load_scene("task6"); }), Contains("task1 ... task5"));
}

TEST_CASE("Wind field: the speed stays within the gustiness, gusts travel with the wind",
          "[core][wind]") {
  WindParameters p;
  p.direction = Vec2(3.0, 4.0);
  p.speed = 6.0;
  p.gustiness = 0.4;
  const WindField wind(p);
  const Vec2 unit = p.direction.normalized();
  double slowest = 1e9, fastest = 0.0;
  for (double t = 0.0; t < 60.0; t += 0.01) {
    const Vec2 w = wind.velocity(t, Vec2(1.0, 2.0));
    CHECK_THAT(w.normalized().dot(unit), WithinAbs(1.0, 1e-12));
    slowest = std::min(slowest, w.norm());
    fastest = std::max(fastest, w.norm());
    // A point 5 m downwind sees the same gust 5/speed seconds later.
    const Vec2 later = wind.velocity(t + 5.0 / p.speed, Vec2(1.0, 2.0) + 5.0 * unit);
    CHECK_THAT(later.norm(), WithinRel(w.norm(), 1e-9));
  }
  CHECK(slowest >= p.speed * (1 - p.gustiness) - 1e-12);
  CHECK(fastest <= p.speed * (1 + p.gustiness) + 1e-12);
  CHECK(fastest - slowest > p.speed * p.gustiness);  // it really gusts
  p.gustiness = 0.0;
  CHECK_THAT(WindField(p).velocity(7.0, Vec2(2.0, 1.0)).norm(), WithinRel(6.0, 1e-12));
}

TEST_CASE("Wind field: passes remember answers only while t and r are unchanged", "[core][wind]") {
  const WindField fresh{WindParameters{}};
  const WindField remembering{WindParameters{}};
  const Vec2 a(1.0, 2.0), b(-3.0, 0.5), moved(1.25, 2.0);  // moved along the wind
  // Four passes over two points: the same, a moved point, a later time, the same again.
  const std::vector<std::pair<double, std::array<Vec2, 2>>> passes{
      {0.3, {a, b}}, {0.3, {moved, b}}, {0.7, {moved, b}}, {0.7, {moved, b}}};
  for (const auto& [t, points] : passes) {
    remembering.begin_pass();
    for (const Vec2& r : points) {
      CAPTURE(t, r);
      const Vec2 w = remembering.velocity(t, r);
      CHECK(w == fresh.velocity(t, r));  // bit for bit
    }
  }
  // The moved point and the later time really change the wind.
  CHECK(fresh.velocity(0.3, a) != fresh.velocity(0.3, moved));
  CHECK(fresh.velocity(0.3, moved) != fresh.velocity(0.7, moved));
}

TEST_CASE("Push: the applied force acts on the chosen particles while t < push_duration",
          "[core][push]") {
  INFO("a free particle under a constant force F for T seconds moves F T^2 / (2 m)");
  SceneParameters p;
  p.structural.enabled = false;
  p.displaced = "none";
  p.pushed = "1";
  p.push = Vec2(0.4, -0.2);
  p.push_duration = 0.5;
  p.integrator = "verlet";  // exact for a constant force
  Simulation sim(p, implementation());
  sim.advance(50);
  const Vec2 a = p.push / p.mass;
  CHECK_THAT(Vec2(sim.particles().position.col(1)),
             IsNear(grid_position(0, 1, 1.0) + 0.5 * a * 0.25, 1e-12));
  CHECK(Vec2(sim.particles().position.col(0)) == grid_position(0, 0, 1.0));
  sim.advance(50);  // afterwards it coasts at a T (to O(h): the push ends inside a step)
  CHECK_THAT(Vec2(sim.particles().velocity.col(1)), IsNear(a * 0.5, a.norm() * p.step));
}

TEST_CASE("Energy: gravity's potential energy makes free fall conserve the total",
          "[core][gravity]") {
  SceneParameters p;
  p.structural.enabled = false;
  p.gravity.enabled = true;
  p.integrator = "verlet";
  Simulation sim(p, implementation());
  const double start = sim.diagnostics().total();
  sim.advance(300);
  const Diagnostics end = sim.diagnostics();
  CHECK(end.kinetic > 1.0);
  CHECK_THAT(end.total(), WithinAbs(start, 1e-9 * end.kinetic));
}

TEST_CASE("A run continued from another goes on in time: the push and the wind do not restart",
          "[core][push]") {
  INFO("the viewer rebuilds a run when a parameter changes; continue_from keeps its clock");
  SceneParameters p = task_scene(5);
  p.rows = p.cols = 4;
  p.pushed = "15";
  p.push = Vec2(2.0, 0.0);
  p.push_duration = 0.3;
  p.integrator = "symplectic-euler";  // no memory of earlier steps: the two runs can agree exactly
  Simulation whole(p, implementation());
  whole.advance(70);
  Simulation first(p, implementation());
  first.advance(40);
  Scene rest = build_scene(p, implementation());
  rest.particles.position = first.particles().position;
  rest.particles.velocity = first.particles().velocity;
  Simulation second(std::move(rest), implementation());
  second.continue_from(first);
  CHECK_THAT(second.time(), WithinAbs(first.time(), 1e-15));
  second.advance(30);
  CHECK_THAT(second.time(), WithinAbs(whole.time(), 1e-12));
  // Equal but for rounding in the time (0.4 + n h against (40 + n) h) that the wind samples.
  CHECK((second.particles().position - whole.particles().position).cwiseAbs().maxCoeff() < 1e-12);
  // Without continue_from the push would act again for 0.3 s: far more than rounding.
  Scene again = build_scene(p, implementation());
  again.particles.position = first.particles().position;
  again.particles.velocity = first.particles().velocity;
  Simulation restarted(std::move(again), implementation());
  restarted.advance(30);
  CHECK((restarted.particles().position - whole.particles().position).cwiseAbs().maxCoeff() > 1e-3);
  CHECK_THAT(second.diagnostics().total(), WithinRel(whole.diagnostics().total(), 1e-12));
}
