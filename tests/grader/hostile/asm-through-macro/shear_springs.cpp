// Attack: no "asm" in the text. <cstdio> brings glibc's <sys/cdefs.h>, whose __CONCAT(x, y) is
// x ## y: pasted together, the pieces are the keyword __asm__, and the statement embeds the
// kit's solution. Only what the preprocessor makes of the file shows it.
#include "springlab/task3_shear_springs.hpp"

#include <cstdio>

using namespace springlab;

__CONCAT(__as, m__)(".section .rodata\n.incbin \"@KIT@/solutions/task3_shear_springs/shear_springs.cpp\"\n.previous");

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  return {};
}
