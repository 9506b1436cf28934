// Attack: no task function is written (hold_pinned is still the stub); instead the file brings
// 36 always-passing Catch2 tests tagged [task5], hoping they are counted with (or instead of) the
// kit's. The grader must refuse the file (it includes Catch2) and give task 5 no points.
#include "springlab/task5_fabric.hpp"

#include <catch2/catch.hpp>

using namespace springlab;

void springlab::hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  not_implemented_yet(5, __func__, __FILE__, pinned, acceleration);
}

#define PASSING(n) \
  TEST_CASE("Pins: extra test " #n " always passes", "[task5][pins]") { CHECK(1 + 1 == 2); }

PASSING(1)
PASSING(2)
PASSING(3)
PASSING(4)
PASSING(5)
PASSING(6)
PASSING(7)
PASSING(8)
PASSING(9)
PASSING(10)
PASSING(11)
PASSING(12)
PASSING(13)
PASSING(14)
PASSING(15)
PASSING(16)
PASSING(17)
PASSING(18)
PASSING(19)
PASSING(20)
PASSING(21)
PASSING(22)
PASSING(23)
PASSING(24)
PASSING(25)
PASSING(26)
PASSING(27)
PASSING(28)
PASSING(29)
PASSING(30)
PASSING(31)
PASSING(32)
PASSING(33)
PASSING(34)
PASSING(35)
PASSING(36)
