// libFuzzer target: any bytes as the text of --set KEY=VALUE (one or several, split at new
// lines), applied to the lab's task 5 scene and validated as the runner does.
#include "springlab/errors.hpp"
#include "springlab/parameters.hpp"
#include "springlab/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  try {
    static const springlab::SceneParameters lab_fabric = springlab::load_scene("task5");
    springlab::SceneParameters p = lab_fabric;
    while (!rest.empty()) {
      const std::size_t end = rest.find('\n');
      springlab::set_assignment(p, rest.substr(0, end));
      rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    }
    springlab::validate(p);
  } catch (const springlab::InvalidParameter&) {
    // The promised answer to bad input.
  }
  return 0;
}
