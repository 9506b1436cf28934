#include "measure.hpp"
namespace springlab::tradeoff {
bool write_figures(const Results&, const std::string&, const std::string&) {
  return false;
}
}  // namespace springlab::tradeoff
