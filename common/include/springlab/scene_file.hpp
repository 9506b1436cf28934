// Scene files: TOML with the same keys as --set, e.g.
//   name = "wide grid"
//   rows = 3
//   cols = 5
//   structural.k = 40        # or a [structural] table with k = 40
//   integrator = "verlet"
// Keys left out keep the lab's values (SceneParameters' defaults).
#pragma once

#include "springlab/parameters.hpp"

#include <string>

namespace springlab {

/// Reads a scene file. Throws InvalidParameter whose message names the file, the line and the
/// key: for TOML syntax errors, unknown keys (with the nearest known one) and bad values.
SceneParameters load_scene_file(const std::string& path);

}  // namespace springlab
