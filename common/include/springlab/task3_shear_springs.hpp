// Task 3: shear springs added to the grid.
// Handout: handout/task3_shear_springs.md. Your files: tasks/task3_shear_springs/. TODO tag: T3.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/task_api.hpp"
#include "springlab/todo.hpp"
#include "springlab/types.hpp"

SPRINGLAB_TASK_API_BEGIN

/// The shear springs of a rows×cols grid, equation (3.1): both diagonals of every grid cell,
/// [i, j]–[i+1, j+1] and [i, j+1]–[i+1, j], so 2·(rows-1)·(cols-1) springs. Indices as in (2.1).
/// Every spring gets the family SpringFamily::shear and the shear family's own k, b and ℓ0
/// (equation (3.2); the lab: k = 7 N/m, b = 0.05 N·s/m, ℓ0 = √2 m).
/// @param rows, cols  grid size (rows ≥ 1, cols ≥ 1)
/// @param family      k (N/m), b (N·s/m) and rest_length (m) of the shear springs
std::vector<Spring> shear_springs(int rows, int cols, const SpringFamilyParameters& family);

SPRINGLAB_TASK_API_END
