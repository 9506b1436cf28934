// Helpers for task 4's verlet_step (task4_verlet.hpp), provided by the kit.
#pragma once

#include "springlab/types.hpp"

namespace springlab {

/// The most velocity estimates one Verlet step may try before it gives up (see verlet_step).
/// Each estimate shrinks the error by about h·c/2 (c: damping per unit mass of the fastest-damped
/// mode), so 100 estimates settle to 1e-12 while h·c/2 < 0.76; beyond that the step gives up.
inline constexpr int verlet_max_iterations = 100;

/// True when two successive velocity estimates of (4.2) agree to rounding: their largest
/// difference is below 1e-12 of the velocity scale max(|v|, |r|/h). (|r|/h because positions carry
/// a rounding error of about 1e-16·|r|, which the division by 2h in (4.2) enlarges.)
bool velocity_settled(const Vectors& v_new, const Vectors& v_old, const Vectors& r, double h);

}  // namespace springlab
