// What every run of the study shares: the reference code, the error and energy of a state
// against the reference at an output time, and Odeint's view of the same model.
#pragma once

#include "odeint_system.hpp"
#include "springlab/implementation.hpp"
#include "springlab/simulation.hpp"
#include "study.hpp"

#include <chrono>

namespace springlab::tradeoff {

/// The kit's reference implementation (solutions/): the force code every method runs on.
const Implementation& lab_implementation();

/// The code `method` runs: lab_implementation(), or for the student's methods the student's
/// task 1 (explicit Euler) or task 4 (Verlet) with the reference for every other task.
const Implementation& implementation_of(const std::string& method);

/// For the student's methods: NotImplemented's message when their task is not written yet
/// (one step of the task 1 scene tells), else "".
std::string not_written(const std::string& method);

/// Largest |r_i - r_ref,i| over the particles, m.
double position_error(const Vectors& r, const Vectors& r_ref);

/// Kinetic + spring + gravity energy (gravity zero at the start positions) of state (r, v) of
/// the scene `sim` runs, whatever its own state is; `start` are the positions at t = 0. J.
double total_energy(const Simulation& sim, const Vectors& r, const Vectors& v,
                    const Vectors& start);

/// The step a method uses between two output times: the output times are every
/// max(sample, h), a whole number of steps for every h = h_lab·2^k.
long steps_between_samples(double sample, double h);

inline double now() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

}  // namespace springlab::tradeoff
