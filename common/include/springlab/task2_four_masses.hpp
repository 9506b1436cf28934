// Task 2: four masses (a 2×2 grid) joined by structural springs, each with a damper.
// Handout: handout/task2_four_masses.md. Your files: tasks/task2_four_masses/. TODO tag: T2.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/task_api.hpp"
#include "springlab/todo.hpp"
#include "springlab/types.hpp"

SPRINGLAB_TASK_API_BEGIN

/// The structural springs of a rows×cols grid, equation (2.2). Particle [i, j] (row i, column j)
/// has index i·cols + j (equation (2.1)). Each particle is joined to its right neighbour [i, j+1]
/// and to the one below it, [i+1, j]: rows·(cols-1) + cols·(rows-1) springs, each pair once.
/// Every spring gets the family SpringFamily::structural and the family's k, b and ℓ0.
/// @param rows, cols  grid size (rows ≥ 1, cols ≥ 1)
/// @param family      k (N/m), b (N·s/m) and rest_length (m) of the structural springs
std::vector<Spring> structural_springs(int rows, int cols, const SpringFamilyParameters& family);

/// Adds every spring's and damper's force to `force`, equations (2.3) and (2.4): for each spring
/// (p, q) compute F_pq = spring_force(...) + damper_force(...) once, add it to particle p and
/// subtract it from particle q (F_qp = -F_pq). `force` is not cleared first.
/// @param springs  the springs, with their own k, b and ℓ0
/// @param r        positions, m              @param v  velocities, m/s
/// @param force    one column per particle, N; the spring forces are added to it
void accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                              const Vectors& v, Vectors& force);

SPRINGLAB_TASK_API_END
