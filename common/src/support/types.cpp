#include "springlab/types.hpp"

namespace springlab {

std::string_view to_string(SpringFamily family) {
  switch (family) {
    case SpringFamily::structural:
      return "structural";
    case SpringFamily::shear:
      return "shear";
    case SpringFamily::bend:
      return "bend";
  }
  return "unknown";
}

}  // namespace springlab
