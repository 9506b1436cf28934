#include "dispatch.hpp"

#include <array>

const springlab::Implementation* springlab_dispatch =
    nullptr;  // declared extern "C" in dispatch.hpp

namespace springlab::grading {
namespace {

std::array<const Implementation*, 6>& references() {
  static std::array<const Implementation*, 6> tables{};
  return tables;
}

}  // namespace

void register_reference(int task, const Implementation& table) {
  references().at(std::size_t(task)) = &table;
}

void take_task(Implementation& into, const Implementation& from, int task) {
  switch (task) {
    case 1:
      into.spring_force = from.spring_force;
      into.damper_force = from.damper_force;
      into.explicit_euler_step = from.explicit_euler_step;
      break;
    case 2:
      into.structural_springs = from.structural_springs;
      into.accumulate_spring_forces = from.accumulate_spring_forces;
      break;
    case 3:
      into.shear_springs = from.shear_springs;
      break;
    case 4:
      into.verlet_step = from.verlet_step;
      break;
    case 5:
      into.bend_springs = from.bend_springs;
      into.add_gravity = from.add_gravity;
      into.add_wind = from.add_wind;
      into.hold_pinned = from.hold_pinned;
      break;
  }
}

void use_table(int graded, const Implementation& graded_functions) {
  static Implementation table;
  table.name = "submission";
  table.student_task = graded;
  for (int task = 1; task <= 5; ++task)
    if (task != graded && references()[std::size_t(task)] != nullptr)
      take_task(table, *references()[std::size_t(task)], task);
  take_task(table, graded_functions, graded);
  springlab_dispatch = &table;
}

}  // namespace springlab::grading
