#include "mistakes.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace springlab::testing {

namespace {

template <class Value, class Distance>
std::string first_match(const std::vector<Suspect<Value>>& suspects, Distance distance,
                        double tolerance) {
  for (const Suspect<Value>& s : suspects)
    if (distance(s.value) <= tolerance) return "likely mistake: " + s.mistake;
  return "";
}

template <class Value>
std::vector<Suspect<Value>> shapes(const Value& expected, const std::string& what) {
  return {{what + " has the opposite sign", Value(-expected)},
          {what + " is twice as large as it should be (counted twice, or a factor 1/2 missing)",
           Value(2.0 * expected)},
          {what + " is half as large as it should be (a factor 2 missing)", Value(0.5 * expected)}};
}

}  // namespace

std::string recognise(double got, const std::vector<Suspect<double>>& suspects, double tolerance) {
  if (!std::isfinite(got))
    return "likely mistake: the value is not a finite number (a division "
           "by zero, or a square root of a negative number?)";
  const auto distance = [got](double v) { return std::abs(got - v); };
  return first_match(suspects, distance, tolerance);
}

std::string recognise(const Vec2& got, const std::vector<Suspect<Vec2>>& suspects,
                      double tolerance) {
  if (!got.allFinite())
    return "likely mistake: the vector is not finite (a division by zero "
           "length, or a square root of a negative number?)";
  const auto distance = [&got](const Vec2& v) { return (got - v).norm(); };
  return first_match(suspects, distance, tolerance);
}

std::string recognise(const Vectors& got, const std::vector<Suspect<Vectors>>& suspects,
                      double tolerance) {
  if (!got.allFinite()) return "likely mistake: some values are not finite numbers";
  return first_match(
      suspects,
      [&got](const Vectors& v) {
        return v.cols() == got.cols() ? (got - v).norm() : std::numeric_limits<double>::infinity();
      },
      tolerance);
}

std::vector<Suspect<double>> usual_suspects(double expected, const std::string& what) {
  std::vector<Suspect<double>> s = shapes(expected, what);
  if (expected != 0.0) s.push_back({what + " is zero: the term is missing", 0.0});
  return s;
}

std::vector<Suspect<Vec2>> usual_suspects(const Vec2& expected, const std::string& what) {
  std::vector<Suspect<Vec2>> s = shapes(expected, what);
  if (!expected.isZero()) s.push_back({what + " is zero: the term is missing", Vec2::Zero()});
  return s;
}

std::string recognise_family(const Spring& spring, SpringFamily family,
                             const SpringFamilyParameters& values, const std::string& equation) {
  const SceneParameters lab;
  std::string said;
  const auto compare = [&](const char* name, double got, double wanted) {
    if (got == wanted) return;
    std::string whose;
    if (got == lab.structural.k || got == lab.structural.b || got == lab.structural.rest_length)
      whose = " (a structural value of the lab scene)";
    else if (got == lab.shear.k || got == lab.shear.b || got == lab.shear.rest_length)
      whose = " (a shear value of the lab scene)";
    std::ostringstream out;
    out << name << " is " << got << whose << " where the family passed in has " << wanted;
    said += (said.empty() ? "" : "; ") + out.str();
  };
  if (spring.family != family)
    said = "the spring is tagged " + std::string(to_string(spring.family)) + ", not " +
           std::string(to_string(family));
  compare("k", spring.k, values.k);
  compare("b", spring.b, values.b);
  compare("the rest length", spring.rest_length, values.rest_length);
  if (said.empty()) return "";
  return "likely mistake: " + said + ": take every value from the family parameter " + equation;
}

std::string recognise_count(long got, long expected, const std::string& what) {
  if (got == expected) return "";
  if (got == 2 * expected)
    return "likely mistake: twice as many " + what +
           " as expected: each pair is joined twice "
           "(once from each end?); join each particle only to its right and lower neighbours";
  if (2 * got == expected)
    return "likely mistake: half as many " + what +
           " as expected: one of two directions is "
           "missing";
  const long difference = std::abs(got - expected);
  const std::string counted =
      std::to_string(difference) + " " + what.substr(0, what.size() - (difference == 1));
  if (got < expected)
    return "likely mistake: " + counted +
           " short: a loop bound one too small (the last row or column left out)?";
  return "likely mistake: " + counted +
         " too many: a loop bound one too large, or a pair "
         "joined twice?";
}

}  // namespace springlab::testing
