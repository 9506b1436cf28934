// The wind of task 5: a mean flow with gusts that are smooth in time, travel along the wind and
// are the same for the same seed on every machine (handout equation (5.4)). Provided by the kit;
// the student's add_wind (task5_fabric.hpp) turns it into a force.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <array>

namespace springlab {

class WindField {
 public:
  /// Draws the gusts of p.seed. p.direction must not be zero (validate() checks it).
  explicit WindField(const WindParameters& p);

  /// w(t, r) = speed · (1 + gustiness · γ(t − (r·d)/speed)) · d, m/s, equation (5.4), where d is
  /// the unit direction and γ ∈ [−1, 1] a sum of three sines with periods near gust_period.
  Vec2 velocity(double t, const Vec2& r) const;

  double drag() const { return drag_; }  ///< c, N·s/m

 private:
  struct Sine {
    double amplitude, angular_frequency, phase;
  };
  Vec2 direction_;
  double speed_, drag_, gustiness_;
  std::array<Sine, 3> gusts_;
};

}  // namespace springlab
