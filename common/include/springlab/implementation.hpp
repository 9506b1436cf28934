// An Implementation is one complete set of the functions students write: the reference
// (solutions/) or "the student's task N with the reference for the other tasks". The core library
// reaches task code only through this table, so a program can run several sets side by side.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/types.hpp"
#include "springlab/wind.hpp"

#include <string_view>
#include <vector>

namespace springlab {

struct Implementation {
  std::string_view name;  ///< its namespace: "reference" or "student_taskN"
  int student_task = 0;   ///< N for "the student's task N", 0 for the reference

  // Task 1 (task1_two_masses.hpp)
  Vec2 (*spring_force)(const Vec2&, const Vec2&, double, double) = nullptr;
  Vec2 (*damper_force)(const Vec2&, const Vec2&, double) = nullptr;
  void (*explicit_euler_step)(const AccelerationFunction&, double, Vectors&, Vectors&) = nullptr;
  // Task 2 (task2_four_masses.hpp)
  std::vector<Spring> (*structural_springs)(int, int, const SpringFamilyParameters&) = nullptr;
  void (*accumulate_spring_forces)(const std::vector<Spring>&, const Vectors&, const Vectors&,
                                   Vectors&) = nullptr;
  // Task 3 (task3_shear_springs.hpp)
  std::vector<Spring> (*shear_springs)(int, int, const SpringFamilyParameters&) = nullptr;
  // Task 4 (task4_verlet.hpp)
  void (*verlet_step)(const AccelerationFunction&, double, Vectors&, Vectors&,
                      VerletHistory&) = nullptr;
  // Task 5 (task5_fabric.hpp)
  std::vector<Spring> (*bend_springs)(int, int, const SpringFamilyParameters&) = nullptr;
  void (*add_gravity)(const Eigen::VectorXd&, const Vec2&, Vectors&) = nullptr;
  void (*add_wind)(const WindField&, double, const Vectors&, const Vectors&, Vectors&) = nullptr;
  void (*hold_pinned)(const std::vector<bool>&, Vectors&) = nullptr;

  /// The solutions' own table points to itself here (a student release's stand-in for them does
  /// not): only that table, never a copy with some functions replaced, lets the kit's model take
  /// its fast path (grid_forces.hpp), which computes what these functions compute.
  const Implementation* kit_model = nullptr;
};

/// Whether impl is the solutions' own table itself (see Implementation::kit_model).
inline bool is_kit_model(const Implementation& impl) {
  return impl.kit_model == &impl;
}

/// The reference implementation (solutions/).
const Implementation& reference_implementation();

/// False only in a student release built where its prebuilt reference cannot be used
/// (common/reference.cmake): reference_implementation() then runs the student's own code, so
/// front ends turn comparisons with it off.
bool reference_is_available();

/// The student's task `task` (1–5) with the reference for every other task: what `./lab test
/// taskN --student` grades. Throws InvalidParameter for a task outside 1–5.
const Implementation& student_implementation(int task);

}  // namespace springlab
