// A running scene's model as a Boost.Odeint system, so that Odeint's steppers (the peers a user
// would pick instead of the kit's integrators) run on exactly the kit's force code. Used by the
// trade-off study and the throughput benchmarks.
//
// Odeint's state is y = (r, v) stacked in one Eigen vector of 4n numbers: r_i at (2i, 2i+1), v_i
// at (2n + 2i, 2n + 2i + 1); its derivative is y' = (v, a(r, v)). The model is autonomous for the
// scenes it is used on (no wind, no push): t is ignored.
#pragma once

#include "springlab/simulation.hpp"

#include <Eigen/Core>
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>

namespace springlab {

using OdeintState = Eigen::VectorXd;

/// y = (r, v) of the particles' current state.
inline OdeintState odeint_state(const Particles& particles) {
  const Eigen::Index n = particles.size();
  OdeintState y(4 * n);
  y.head(2 * n) = particles.position.reshaped();
  y.tail(2 * n) = particles.velocity.reshaped();
  return y;
}

/// The positions r (m) held in y, as a 2×n matrix view.
inline auto odeint_positions(const OdeintState& y) {
  return y.head(y.size() / 2).reshaped(2, y.size() / 4);
}

/// The velocities v (m/s) held in y, as a 2×n matrix view.
inline auto odeint_velocities(const OdeintState& y) {
  return y.tail(y.size() / 2).reshaped(2, y.size() / 4);
}

/// y' = (v, a(r, v)) with a the simulation's acceleration (every force it enables, pins held).
/// Each call is one force evaluation, counted by simulation.force_evaluations().
class OdeintSystem {
 public:
  explicit OdeintSystem(Simulation& simulation) : simulation_(&simulation) {}

  void operator()(const OdeintState& y, OdeintState& dydt, double /*t*/) {
    const Eigen::Index half = y.size() / 2;
    // Copies into 2×n matrices because the model takes Vectors: 4n numbers against the work of
    // every spring, about 1 % of an evaluation.
    r_ = odeint_positions(y);
    v_ = odeint_velocities(y);
    dydt.resize(y.size());
    dydt.head(half) = y.tail(half);
    dydt.tail(half) = simulation_->acceleration(r_, v_).reshaped();
  }

 private:
  Simulation* simulation_;
  Vectors r_, v_;
};

/// Odeint's classical Runge–Kutta and Dormand–Prince 5(4) steppers over Eigen vectors.
using OdeintRk4 =
    boost::numeric::odeint::runge_kutta4<OdeintState, double, OdeintState, double,
                                         boost::numeric::odeint::vector_space_algebra>;
using OdeintDopri5 =
    boost::numeric::odeint::runge_kutta_dopri5<OdeintState, double, OdeintState, double,
                                               boost::numeric::odeint::vector_space_algebra>;

}  // namespace springlab
