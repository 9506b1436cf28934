// Scenes are data: parameters go in, particles and springs come out. Built in this one place and
// shared by the runner, the viewer, the tests and the benchmarks.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <string>
#include <utility>
#include <vector>

namespace springlab {

struct Scene {
  SceneParameters parameters;   ///< what it was built from
  Particles particles;          ///< at t = 0, the displaced particle already moved
  std::vector<Spring> springs;  ///< only the families the parameters enable
};

/// Position of grid particle [row, col] at rest: x = col·spacing, y = -row·spacing (row 0 on top).
Vec2 grid_position(int row, int col, double spacing);

/// Builds the grid after validate(p): equal masses at grid_position, at rest, then the displaced
/// particles moved and the pinned ones flagged; springs from impl's builders for the enabled
/// families only (a scene pays for nothing it leaves out).
Scene build_scene(const SceneParameters& p, const Implementation& impl);

/// The first particle whose position or velocity is not a finite number, with the component
/// ("position.x", …, "velocity.y"); {-1, ""} when every value is finite.
std::pair<int, std::string> first_non_finite(const Particles& particles);

/// Checks a scene built or changed elsewhere: its parameters (validate), matching particle
/// arrays, finite positions and velocities, positive masses, springs between two different
/// existing particles with k ≥ 0, b ≥ 0 and ℓ0 > 0. Throws InvalidParameter naming the field.
void validate(const Scene& scene);

/// The lab's scene for task 1–5 (handout sections 1–5), read from common/scenes/taskN.toml as
/// compiled into the kit. Throws InvalidParameter for any other number.
SceneParameters task_scene(int task);

/// "task1" … "task5", then "task4-damped" (task 4's grid, dampers 4 × the lab's, h = 0.085 s,
/// where textbook Verlet diverges and the lab's does not: handout section 4).
std::vector<std::string> task_scene_names();

/// A built-in scene (task_scene_names); otherwise the scene file at that path (scene_file.hpp).
SceneParameters load_scene(const std::string& name_or_path);

}  // namespace springlab
