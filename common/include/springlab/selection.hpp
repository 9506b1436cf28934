// Sets of particles written as text, for pins, initial displacements and applied forces:
//   "none", "all", "top-row", "bottom-row", "left-column", "right-column", "top-corners",
//   "corners", particle indices and ranges, or several of these separated by commas, e.g.
//   "0,4,8", "0-9,15" or "top-corners,14".
// Indices follow equation (2.1): particle [row, col] is row·cols + col, row 0 on top.
#pragma once

#include <string_view>
#include <vector>

namespace springlab {

/// The particles `text` names in a rows×cols grid, sorted, each once. Throws InvalidParameter
/// naming `field`, the text and the forms allowed, for text that is none of the forms above or
/// an index outside 0 … rows·cols − 1.
std::vector<int> select_particles(std::string_view field, std::string_view text, int rows,
                                  int cols);

}  // namespace springlab
