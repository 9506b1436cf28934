// Attack: the shear springs as the solution has them, and inline assembler after a line
// marker written '#', form feed, '1 "/usr/include/stdlib.h" 3'. GCC reads a form feed as a
// blank, so it obeys the marker and takes the lines after it for a system header's; a lexer
// that does not, sees no directive there, and a check of the preprocessor's output that
// trusts the markers checks none of them.
// Task 3: the shear springs of a grid. Handout section 3.
#include "springlab/task3_shear_springs.hpp"

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
  const auto index = [cols](int row, int col) { return row * cols + col; };  // (2.1)
  std::vector<Spring> springs;
  springs.reserve(std::size_t(2 * (rows - 1) * (cols - 1)));
  const auto join = [&](int p, int q) {
    springs.push_back({p, q, SpringFamily::shear, family.k, family.b, family.rest_length});
  };
  for (int row = 0; row + 1 < rows; ++row)
    for (int col = 0; col + 1 < cols; ++col) {  // (3.1): both diagonals of each cell
      join(index(row, col), index(row + 1, col + 1));
      join(index(row, col + 1), index(row + 1, col));
    }
  return springs;
}
#define JOIN(a, b) a##b  // no keyword in the text: the preprocessor pastes it together
#1 "/usr/include/stdlib.h" 3
JOIN(__as, m__)(".pushsection .rodata\n.ascii \"bytes of the submission's choosing\"\n.popsection");
