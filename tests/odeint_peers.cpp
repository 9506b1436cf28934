// The Boost.Odeint peers (tests/measure/odeint_system.hpp) run on the kit's own force code: the
// same method on the same model gives the same motion, and the adaptive Dormand–Prince stepper
// meets its tolerance against the exact two-mass solution.
#include "lab_testing.hpp"
#include "odeint_system.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>

using namespace springlab;
using namespace springlab::testing;
namespace odeint = boost::numeric::odeint;

TEST_CASE("Odeint peers: Odeint's RK4 on the kit's model steps exactly like the kit's rk4",
          "[integrators][odeint]") {
  SceneParameters p = task_scene(4);  // the 3x3 grid, a particle pulled out
  p.integrator = "rk4";
  Simulation kit(p, implementation());
  Simulation peer(p, implementation());
  OdeintState y = odeint_state(peer.particles());
  OdeintSystem system(peer);
  const int steps = 500;
  odeint::integrate_n_steps(OdeintRk4(), std::ref(system), y, 0.0, p.step, steps);
  kit.advance(steps);
  CHECK(peer.force_evaluations() == 4 * steps);
  // The same arithmetic in another order: equal to rounding, far below the method's error.
  const double scale = kit.particles().position.cwiseAbs().maxCoeff();
  CHECK((Vectors(odeint_positions(y)) - kit.particles().position).cwiseAbs().maxCoeff() <
        1e-12 * scale);
  CHECK((Vectors(odeint_velocities(y)) - kit.particles().velocity).cwiseAbs().maxCoeff() < 1e-10);
  // And the motion is not trivial: the pulled particle has moved.
  CHECK((kit.particles().position - Simulation(p, implementation()).particles().position)
            .cwiseAbs()
            .maxCoeff() > 0.01);
}

TEST_CASE("Odeint peers: adaptive Dormand-Prince meets its tolerance on the two masses",
          "[integrators][odeint]") {
  const SceneParameters p = task_scene(1);  // particle 1 displaced by 0.2 m along the spring
  const TwoMassExact exact{p.structural.k, p.structural.b, p.mass, p.displacement.x()};
  for (const double tolerance : {1e-4, 1e-8}) {
    Simulation peer(p, implementation());
    OdeintState y = odeint_state(peer.particles());
    OdeintSystem system(peer);
    const double end = 5.0;  // s
    odeint::integrate_adaptive(odeint::make_controlled(tolerance, tolerance, OdeintDopri5()),
                               std::ref(system), y, 0.0, end, p.step);
    const Vectors r = odeint_positions(y);
    const double stretch = (r.col(1) - r.col(0)).norm() - p.structural.rest_length;
    INFO("tolerance " << tolerance);
    // The global error of a well-damped oscillation stays within a small multiple of the
    // per-step tolerance; a tenth of the tolerance would say it did far more work than asked.
    CHECK(std::abs(stretch - exact.stretch(end)) < 100 * tolerance);
  }
}
