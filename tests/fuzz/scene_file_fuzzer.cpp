// libFuzzer target: any bytes as a scene file. The kit must answer every input with a scene or
// InvalidParameter; anything else (a crash, a sanitizer report, another exception) is a finding.
#include "springlab/errors.hpp"
#include "springlab/scene_file.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    springlab::parse_scene(text, "fuzz.toml");
  } catch (const springlab::InvalidParameter&) {
    // The promised answer to bad input.
  }
  return 0;
}
