// The lab's scenes as the kit ships them: the text of common/scenes/NAME.toml, compiled in.
#pragma once

#include <string_view>
#include <vector>

namespace springlab {

struct BuiltinScene {
  std::string_view name;  ///< "task1" … "task5", "task4-damped"
  std::string_view path;  ///< the file it came from, for error messages
  std::string_view text;  ///< its TOML
};

const std::vector<BuiltinScene>& builtin_scenes();

}  // namespace springlab
