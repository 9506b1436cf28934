// The linear model of the forces that ran, measured from the code under test about rest: a step
// limit the diagnosis says of a run comes from these forces, not from (1.1) and (1.2) (issue 39).
// Private to the core library.
#pragma once

#include "springlab/implementation.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"

#include <optional>

namespace springlab::internal {

/// K = -M ∂a/∂r and C = -M ∂a/∂v of impl's model of `scene` at (rest, 0), by central differences,
/// one free coordinate at a time (4 evaluations of the model each); gravity, wind and push off
/// (they add no stiffness, and the wind's drag is added as the kit's formula adds it). Both
/// matrices are made symmetric, as the stability formulas expect. Empty when the code throws or
/// gives a value that is not finite.
std::optional<LinearModel> measured_model(const Scene& scene, const Implementation& impl,
                                          const Vectors& rest);

/// How far a measured model is from an expected one: the largest entry of each difference (K and
/// C apart) over the largest entry of the expected matrix (or 1 when it is zero); the larger.
double model_gap(const LinearModel& measured, const LinearModel& expected);

}  // namespace springlab::internal
