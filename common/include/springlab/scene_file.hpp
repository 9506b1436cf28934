// Scene files: TOML with the same keys as --set, e.g.
//   name = "wide grid"
//   rows = 3
//   cols = 5
//   structural.k = 40        # or a [structural] table with k = 40
//   integrator = "verlet"
//   pinned = "top-row"       # particle sets as in selection.hpp
// Keys left out keep the lab's values (SceneParameters' defaults). The lab's own scenes are
// such files: common/scenes/task1.toml … task5.toml.
#pragma once

#include "springlab/parameters.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace springlab {

/// The largest scene file read, bytes: the lab's scenes have a few hundred.
inline constexpr std::uintmax_t max_scene_file_bytes = 1 << 20;

/// Reads a scene file. Throws InvalidParameter whose message names the file, the line and the
/// key: for TOML syntax errors, unknown keys (with the nearest known one) and bad values.
SceneParameters load_scene_file(const std::string& path);

/// Reads a scene from TOML text; `path` names it in error messages (the built-in scenes are the
/// files common/scenes/taskN.toml, compiled into the kit).
SceneParameters parse_scene(std::string_view text, const std::string& path);

}  // namespace springlab
