// Attack on whoever reads the feedback in a terminal: shear_springs throws (so every test fails
// and its output is shown) after printing terminal escape sequences (clear the
// screen, set the window title, move the cursor, a hyperlink), a bell, backspaces and carriage
// returns that would overwrite "FAIL" with "pass", NUL bytes and invalid UTF-8. The feedback
// must keep none of these control bytes (they become '?'), and results.json must stay valid.
#include "springlab/task3_shear_springs.hpp"

#include <cstdio>
#include <stdexcept>

using namespace springlab;

std::vector<Spring> springlab::shear_springs(int, int, const SpringFamilyParameters&) {
  static const char nasty[] =
      "\x1b[2J\x1b[H\x1b]0;all tests pass\x07"         // clear, home, window title
      "\x1b]8;;https://example.invalid/\x1b\\link\x1b]8;;\x1b\\"  // a hyperlink
      "\x1b[1A\x1b[2K  Shear springs ... pass\r\b\b\b\bpass\n"   // cursor up, erase, overwrite
      "NUL:\0:NUL bad UTF-8: \xff\xfe\xc3\x28 \xed\xa0\x80 end\n";
  std::fwrite(nasty, 1, sizeof nasty - 1, stdout);
  std::fflush(stdout);
  throw std::runtime_error("\x1b[32mall tests pass\x1b[0m");
}
