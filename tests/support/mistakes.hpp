// Mistake recognisers: when a test's value differs from the physics, the common shapes of error
// (the opposite sign, a factor 2 or 1/2, a missing term, a value computed another way) named in
// a student's words. A test computes the candidate wrong values itself and passes them with
// their names; the first one the student's value matches is said, as an INFO line that the
// grader's reporter shows under "likely mistake" (tests/feedback/reporter.cpp).
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <string>
#include <vector>

namespace springlab::testing {

/// A value a known mistake would give, and the words that name that mistake.
template <class Value>
struct Suspect {
  std::string mistake;  ///< e.g. "the opposite sign: equation (1.1) starts with a minus"
  Value value;
};

/// "likely mistake: <words>" for the first suspect within `tolerance` of `got` (Euclidean
/// distance for vectors, absolute for numbers), else "" (an INFO of "" shows nothing).
std::string recognise(double got, const std::vector<Suspect<double>>& suspects, double tolerance);
std::string recognise(const Vec2& got, const std::vector<Suspect<Vec2>>& suspects,
                      double tolerance);
std::string recognise(const Vectors& got, const std::vector<Suspect<Vectors>>& suspects,
                      double tolerance);

/// The shapes any value can take when a formula is almost right, with `what` naming it (e.g.
/// "the spring force (1.1)"): minus the expected value, twice it, half of it, zero, not a number.
std::vector<Suspect<double>> usual_suspects(double expected, const std::string& what);
std::vector<Suspect<Vec2>> usual_suspects(const Vec2& expected, const std::string& what);

/// "likely mistake: ..." naming what a spring carries other than the family's `values` (its tag,
/// k, b or rest length, saying when the value is another family's in the lab scene), or "".
std::string recognise_family(const Spring& spring, SpringFamily family,
                             const SpringFamilyParameters& values, const std::string& equation);

/// `INFO`'s text for a count (`what` in the plural, e.g. "springs") that differs from the
/// expected one: twice (each pair in both
/// orders), half (one of two directions), or a few short (a loop bound one too small).
std::string recognise_count(long got, long expected, const std::string& what);

}  // namespace springlab::testing
