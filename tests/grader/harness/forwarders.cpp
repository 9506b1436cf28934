// The task functions as the kit's tests call them, in the harness's namespace (SPRINGLAB_IMPL =
// graded): each one calls the function of the submission library that main.cpp loaded, so the
// tests, compiled once, run against any submission.
#include "forwarders.hpp"

#include "springlab/task1_two_masses.hpp"
#include "springlab/task2_four_masses.hpp"
#include "springlab/task3_shear_springs.hpp"
#include "springlab/task4_verlet.hpp"
#include "springlab/task5_fabric.hpp"
#include "springlab/this_implementation.hpp"

namespace springlab::grading {
namespace {
const Implementation* loaded_table = nullptr;
}

void use_submission(const Implementation& table) {
  loaded_table = &table;
}

}  // namespace springlab::grading

using namespace springlab;
using grading::loaded_table;

const Implementation& springlab::implementation() {
  return *loaded_table;
}

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  return loaded_table->spring_force(r_p, r_q, k, rest_length);
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return loaded_table->damper_force(v_p, v_q, b);
}

void springlab::explicit_euler_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                                    Vectors& v) {
  loaded_table->explicit_euler_step(acceleration, h, r, v);
}

std::vector<Spring> springlab::structural_springs(int rows, int cols,
                                                  const SpringFamilyParameters& family) {
  return loaded_table->structural_springs(rows, cols, family);
}

void springlab::accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                                         const Vectors& v, Vectors& force) {
  loaded_table->accumulate_spring_forces(springs, r, v, force);
}

std::vector<Spring> springlab::shear_springs(int rows, int cols,
                                             const SpringFamilyParameters& family) {
  return loaded_table->shear_springs(rows, cols, family);
}

void springlab::verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                            Vectors& v, VerletHistory& history) {
  loaded_table->verlet_step(acceleration, h, r, v, history);
}

std::vector<Spring> springlab::bend_springs(int rows, int cols,
                                            const SpringFamilyParameters& family) {
  return loaded_table->bend_springs(rows, cols, family);
}

void springlab::add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  loaded_table->add_gravity(mass, g, force);
}

void springlab::add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                         Vectors& force) {
  loaded_table->add_wind(wind, t, r, v, force);
}

void springlab::hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  loaded_table->hold_pinned(pinned, acceleration);
}
