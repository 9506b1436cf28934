// A reference motion for scenes without an exact solution, computed on the kit's own force code
// by two independent methods, each checked against a refined run of itself.
#pragma once

#include "study.hpp"

namespace springlab::tradeoff {

struct ComputedReference {
  Trajectory trajectory;
  double error = 0.0;  ///< m, its estimated largest position error
  std::string note;    ///< what was compared and which one won, for the page
};

ComputedReference compute_reference(const Scenario& s, const StudyOptions& options);

/// Odeint's Dormand–Prince at abs = rel = tolerance, with dense output at the output times.
Trajectory dopri5_trajectory(const Scenario& s, double tolerance, const StudyOptions& options,
                             long* evaluations = nullptr);

/// The kit's rk4 at step h (h divides the output interval).
Trajectory rk4_trajectory(const Scenario& s, double h, const StudyOptions& options);

/// The largest position difference of two trajectories over their common output times, m.
double largest_difference(const Trajectory& a, const Trajectory& b);

}  // namespace springlab::tradeoff
