// The runner's CSV: a header row, then one row per output step.
#pragma once

#include "springlab/simulation.hpp"

#include <ostream>

namespace springlab {

/// t, then x{i},y{i},vx{i},vy{i} for every particle i (0-based), then kinetic,potential,px,py
/// (potential: springs and gravity together, as in the summary and the viewer's plot).
void write_csv_header(std::ostream& out, int particles);

/// One row for the simulation's current state; numbers in the shortest form that reads back
/// exactly.
void write_csv_row(std::ostream& out, const Simulation& simulation);

}  // namespace springlab
