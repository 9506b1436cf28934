// Task 5: a fabric, an n×m grid with structural, shear and bend springs, gravity, wind and pins.
// Handout: handout/task5_fabric.md. Your files: tasks/task5_fabric/. TODO tag: T5.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/task_api.hpp"
#include "springlab/todo.hpp"
#include "springlab/types.hpp"
#include "springlab/wind.hpp"

#include <vector>

SPRINGLAB_TASK_API_BEGIN

/// The bend springs of a rows×cols grid, equation (5.1): each particle [i, j] is joined to the
/// particle two places to its right, [i, j+2], and two places below it, [i+2, j]:
/// rows·max(cols-2, 0) + cols·max(rows-2, 0) springs. Indices as in (2.1).
/// Every spring gets the family SpringFamily::bend and the bend family's k, b and ℓ0 (the kit's
/// values: k = 10 N/m, b = 0.05 N·s/m, ℓ0 = 2 m).
/// @param rows, cols  grid size (rows ≥ 1, cols ≥ 1)
/// @param family      k (N/m), b (N·s/m) and rest_length (m) of the bend springs
std::vector<Spring> bend_springs(int rows, int cols, const SpringFamilyParameters& family);

/// Adds gravity to every particle's force, equation (5.2): F_i += m_i g.
/// @param mass   m_i of every particle, kg
/// @param g      the acceleration of gravity, m/s² (the kit's value: (0, -9.81), y points up)
/// @param force  one column per particle, N; gravity is added to it
void add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force);

/// Adds the wind's drag to every particle's force, equation (5.3):
///   F_i += c (w(t, r_i) - v_i),
/// where w = wind.velocity(t, r_i) is the wind's velocity at the particle (equation (5.4), given
/// by the kit) and c = wind.drag(). A particle moving with the wind feels no force.
/// @param wind   the wind field: velocity(t, r) in m/s and drag() in N·s/m
/// @param t      time, s
/// @param r      positions, m               @param v  velocities, m/s
/// @param force  one column per particle, N; the wind's force is added to it
void add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v, Vectors& force);

/// Pins, equation (5.5): a pinned particle never moves, so its acceleration is zero, a_i = 0,
/// whatever forces act on it. The model calls this on the accelerations of every step; with
/// v_i = 0 at the start, every integrator then leaves a pinned particle exactly where it is.
/// @param pinned        one flag per particle, true for pinned
/// @param acceleration  one column per particle, m/s²; the pinned particles' columns are zeroed
void hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration);

SPRINGLAB_TASK_API_END
