#include "measure.hpp"
namespace springlab::tradeoff {
void write_page(const Results&, const std::string&, const std::string&) {}
}  // namespace springlab::tradeoff
