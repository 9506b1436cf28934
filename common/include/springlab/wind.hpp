// The wind of task 5: a mean flow with gusts that are smooth in time, travel along the wind and
// are the same for the same seed on every machine (handout equation (5.4)). Provided by the kit;
// the student's add_wind (task5_fabric.hpp) turns it into a force.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace springlab {

class WindField {
 public:
  /// Draws the gusts of p.seed. p.direction must not be zero (validate() checks it).
  explicit WindField(const WindParameters& p);

  /// w(t, r) = speed · (1 + gustiness · γ(t − (r·d)/speed)) · d, m/s, equation (5.4), where d is
  /// the unit direction and γ ∈ [−1, 1] a sum of three sines with periods near gust_period.
  Vec2 velocity(double t, const Vec2& r) const;
  /// w(t, r_j) for `count` particles (x and y of each in turn, in r and in w), always computed,
  /// never remembered, so safe to call from several threads. Vectorised: it agrees with
  /// velocity() to a few units in the last place of the gusts, not to the bit.
  void velocities(double t, const double* r, int count, double* w) const;

  double drag() const { return drag_; }  ///< c, N·s/m

  /// Starts a pass over the particles, asked in the same order every time (Simulation calls it
  /// before each add_wind). All evaluations of a(r, v) within a step ask for the wind at the step's
  /// start time, and Verlet's velocity iterations at the same positions too: from the first call
  /// of begin_pass on, velocity() remembers the last pass's answers in order and returns them when
  /// t and r are the same, bit for bit what it would compute, without the three sines.
  void begin_pass() const { cursor_ = 0, remembering_ = true; }

 private:
  struct Sine {
    double amplitude, angular_frequency, phase;
  };
  struct Answer {
    double t;
    Vec2 r, w;
  };
  Vec2 compute(double t, const Vec2& r) const;
  Vec2 direction_;
  double speed_, drag_, gustiness_;
  std::array<Sine, 3> gusts_;
  mutable std::vector<Answer> answers_;  // the last pass's, in the order asked
  mutable std::size_t cursor_ = 0;
  mutable bool remembering_ = false;
};

}  // namespace springlab
