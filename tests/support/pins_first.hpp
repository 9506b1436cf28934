// A check for task 5's later tests, which all go through hold_pinned: when one of them fails
// because hold_pinned is wrong, it says so instead of blaming the law it is about (issue 39).
#pragma once

#include "exception_names.hpp"
#include "springlab/task5_fabric.hpp"

#include <sstream>
#include <string>
#include <vector>

namespace springlab::testing {

// "" when the code under test's hold_pinned zeroes exactly the pinned particles of `pinned`;
// otherwise the words for a later test that goes through it: a failure there is hold_pinned's,
// checked here on this scene's own pins, not the law that test is about.
inline std::string pins_first(const std::vector<bool>& pinned) {
  const auto n = Eigen::Index(pinned.size());
  Vectors a(2, n);
  for (Eigen::Index i = 0; i < n; ++i)
    a.col(i) = Vec2(1.0 + double(i), -0.5 - double(i));
  Vectors held = a;
  try {
    hold_pinned(pinned, held);
  } catch (...) {
    return "likely mistake: this test goes through hold_pinned (5.5), which threw " +
           current_exception_text() +
           " on this scene's pins; fix it first (its own test, 'Pins: hold_pinned zeroes the "
           "pinned particles' accelerations and no others', fails too)";
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool is_pinned = pinned[std::size_t(i)];
    if (Vec2(held.col(i)) == (is_pinned ? Vec2::Zero() : Vec2(a.col(i)))) continue;
    std::ostringstream out;
    out << "likely mistake: this test goes through hold_pinned (5.5), which is wrong on this "
           "scene's pins: "
        << (is_pinned ? "it left the acceleration of pinned particle "
                      : "it changed the acceleration of free particle ")
        << i << (is_pinned ? ", which (5.5) sets to zero" : ", which (5.5) leaves as it is")
        << "; fix hold_pinned first (its own test, 'Pins: hold_pinned zeroes the pinned "
           "particles' accelerations and no others', fails too)";
    return out.str();
  }
  return "";
}

}  // namespace springlab::testing
