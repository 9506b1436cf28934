#include "springlab/types.hpp"

namespace springlab {

std::string_view to_string(SpringFamily family) {
  switch (family) {
    case SpringFamily::structural:
      return "structural";
    case SpringFamily::shear:
      return "shear";
  }
  return "unknown";
}

}  // namespace springlab
