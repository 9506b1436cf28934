#include "springlab/wind.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace springlab {

WindField::WindField(const WindParameters& p)
    : direction_(p.direction.normalized()),
      speed_(p.speed),
      drag_(p.drag),
      gustiness_(p.gustiness) {
  // Raw 32-bit draws of mt19937, whose sequence the C++ standard fixes: the distributions of
  // <random> may differ between standard libraries, these fractions do not.
  std::mt19937 bits(static_cast<std::mt19937::result_type>(p.seed));
  const auto fraction = [&bits] { return double(bits()) / 4294967296.0; };  // in [0, 1)
  double total = 0.0;
  for (Sine& sine : gusts_) {
    sine.amplitude = 0.2 + fraction();
    sine.angular_frequency = 2.0 * std::numbers::pi / (p.gust_period * (0.5 + fraction()));
    sine.phase = 2.0 * std::numbers::pi * fraction();
    total += sine.amplitude;
  }
  for (Sine& sine : gusts_)
    sine.amplitude /= total;  // so |γ| ≤ 1 and the speed never turns negative
}

Vec2 WindField::velocity(double t, const Vec2& r) const {
  if (!remembering_) return compute(t, r);
  const std::size_t i = cursor_++;
  if (i == answers_.size()) answers_.push_back({t, r, compute(t, r)});
  Answer& answer = answers_[i];
  if (answer.t != t || answer.r != r) answer = {t, r, compute(t, r)};
  return answer.w;
}

Vec2 WindField::compute(double t, const Vec2& r) const {
  // A gust reaches a point downwind later: it travels with the mean flow.
  const double s = speed_ > 0.0 ? t - r.dot(direction_) / speed_ : t;
  double gust = 0.0;
  for (const Sine& sine : gusts_)
    gust += sine.amplitude * std::sin(sine.angular_frequency * s + sine.phase);
  return speed_ * (1.0 + gustiness_ * gust) * direction_;
}

}  // namespace springlab
