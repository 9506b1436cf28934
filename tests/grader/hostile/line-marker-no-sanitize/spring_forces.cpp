// Attack: a read past the end of the springs that AddressSanitizer would catch, in a function
// marked no_sanitize, after a line marker written '#', backslash, form feed, line end,
// '1 "/usr/include/stdlib.h" 3': GCC joins the two lines (blanks may stand between a
// backslash and the line end) and obeys the marker; a lexer that does not join them sees a
// null directive. Unchecked, the attribute would keep the sanitized run from seeing the error.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"

#define JOIN(a, b) a##b  // no keyword in the text: the preprocessor pastes it together
#\
1 "/usr/include/stdlib.h" 3

using namespace springlab;

JOIN(__attri, bute__)((no_sanitize("address"))) void springlab::accumulate_spring_forces(
    const std::vector<Spring>& springs, const Vectors& r, const Vectors& v, Vectors& force) {
  double unused = 0.0;
  if (!springs.empty()) unused = springs.data()[springs.capacity()].k;  // one past the end
  for (const Spring& s : springs) {
    const Vec2 f = spring_force(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                   damper_force(v.col(s.p), v.col(s.q), s.b) + Vec2::Constant(0.0 * unused);
    force.col(s.p) += f;
    force.col(s.q) -= f;
  }
}
