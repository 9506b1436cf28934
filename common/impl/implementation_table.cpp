// Compiled once into every implementation build (see task_api.hpp), with SPRINGLAB_IMPL naming
// its namespace and SPRINGLAB_STUDENT_TASK saying which task comes from the student's files.
#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"
#include "springlab/task3_shear_springs.hpp"
#include "springlab/task4_verlet.hpp"
#include "springlab/task5_fabric.hpp"
#include "springlab/this_implementation.hpp"

#ifndef SPRINGLAB_STUDENT_TASK
#error "SPRINGLAB_STUDENT_TASK is not set"
#endif

// 1 only where the build says the solutions' own files are inside (common/implementations.cmake);
// anywhere else (the grader's programs) the kit's fast path stays off.
#ifndef SPRINGLAB_SOLUTIONS_INSIDE
#define SPRINGLAB_SOLUTIONS_INSIDE 0
#endif

#define SPRINGLAB_TEXT(x) #x
#define SPRINGLAB_NAME(x) SPRINGLAB_TEXT(x)

const springlab::Implementation& springlab::implementation() {
  static const Implementation table{
      .name = SPRINGLAB_NAME(SPRINGLAB_IMPL),
      .student_task = SPRINGLAB_STUDENT_TASK,
      .spring_force = &spring_force,
      .damper_force = &damper_force,
      .explicit_euler_step = &explicit_euler_step,
      .structural_springs = &structural_springs,
      .accumulate_spring_forces = &accumulate_spring_forces,
      .shear_springs = &shear_springs,
      .verlet_step = &verlet_step,
      .bend_springs = &bend_springs,
      .add_gravity = &add_gravity,
      .add_wind = &add_wind,
      .hold_pinned = &hold_pinned,
      .kit_model = SPRINGLAB_STUDENT_TASK == 0 && SPRINGLAB_SOLUTIONS_INSIDE ? &table : nullptr,
  };
  return table;
}
