// The computed reference: Odeint's adaptive Dormand–Prince at tolerance 1e-12 and the kit's RK4
// at a step 128 times below the lab's, each checked against a refined run of itself (tolerance
// 1e-13, step halved). The refined run of the method whose check shows the smaller difference is
// the reference; that difference is kept as its (generous) error estimate.
#include "reference.hpp"

#include "measure.hpp"
#include "springlab/scene.hpp"

#include <cmath>
#include <iostream>

namespace springlab::tradeoff {

namespace odeint = boost::numeric::odeint;

Trajectory dopri5_trajectory(const Scenario& s, double tolerance, const StudyOptions& options,
                             long* evaluations) {
  Simulation sim(s.params, lab_implementation());
  const Vectors start = sim.particles().position;
  OdeintState y = odeint_state(sim.particles());
  OdeintSystem system(sim);
  std::vector<double> times;
  const long samples = std::lround(options.duration / options.sample);
  for (long j = 0; j <= samples; ++j)
    times.push_back(double(j) * options.sample);
  Trajectory out;
  auto observe = [&](const OdeintState& state, double t) {
    const Vectors r = odeint_positions(state), v = odeint_velocities(state);
    out.time.push_back(t);
    out.position.push_back(r);
    out.energy.push_back(total_energy(sim, r, v, start));
  };
  odeint::integrate_times(odeint::make_dense_output(tolerance, tolerance, OdeintDopri5()),
                          std::ref(system), y, times.begin(), times.end(), s.params.step, observe);
  if (evaluations) *evaluations = sim.force_evaluations();
  return out;
}

Trajectory rk4_trajectory(const Scenario& s, double h, const StudyOptions& options) {
  SceneParameters p = s.params;
  set_number(p, "step", h);
  set_parameter(p, "integrator", "rk4");
  Simulation sim(p, lab_implementation());
  const long per_sample = steps_between_samples(options.sample, h);
  const long samples = std::lround(options.duration / options.sample);
  Trajectory out;
  for (long j = 0; j <= samples; ++j) {
    if (j > 0) sim.advance(per_sample);
    out.time.push_back(double(j) * options.sample);
    out.position.push_back(sim.particles().position);
    out.energy.push_back(sim.diagnostics().total());
  }
  return out;
}

double largest_difference(const Trajectory& a, const Trajectory& b) {
  double largest = 0.0;
  for (std::size_t j = 0; j < a.position.size() && j < b.position.size(); ++j)
    largest = std::max(largest, position_error(a.position[j], b.position[j]));
  return largest;
}

ComputedReference compute_reference(const Scenario& s, const StudyOptions& options) {
  const double started = now();
  std::cerr << "tradeoff: " << s.name << ": computing the reference (dopri5 at 1e-12 and 1e-13, "
            << "rk4 at h_lab/128 and h_lab/256)\n";
  const double h_rk4 = s.params.step / 128.0;
  const Trajectory dopri = dopri5_trajectory(s, 1e-12, options);
  Trajectory dopri_fine = dopri5_trajectory(s, 1e-13, options);
  const Trajectory rk4 = rk4_trajectory(s, h_rk4, options);
  Trajectory rk4_fine = rk4_trajectory(s, h_rk4 / 2.0, options);
  const double d_dopri = largest_difference(dopri, dopri_fine);
  const double d_rk4 = largest_difference(rk4, rk4_fine);
  const double d_between = largest_difference(dopri_fine, rk4_fine);
  ComputedReference ref;
  const bool dopri_wins = d_dopri < d_rk4;
  ref.trajectory = dopri_wins ? std::move(dopri_fine) : std::move(rk4_fine);
  // The refined run is more accurate than its difference to its coarser twin (by about 10x for
  // dopri5, 16x for rk4): that difference is a generous bound of its error.
  ref.error = dopri_wins ? d_dopri : d_rk4;
  ref.note =
      "computed on the kit's force code. Odeint's runge_kutta_dopri5 at tolerance 1e-12 "
      "differs from itself at 1e-13 by at most " +
      number(d_dopri) + " m; the kit's rk4 at h = " + number(h_rk4) +
      " s differs from itself at h/2 by " + number(d_rk4) + " m; the two refined runs differ by " +
      number(d_between) + " m. The reference is " +
      (dopri_wins ? std::string("dopri5 at 1e-13") : "rk4 at h = " + number(h_rk4 / 2)) +
      ", the one whose own check is tighter; its error is taken as at most " + number(ref.error) +
      " m";
  std::cerr << "tradeoff: " << s.name << ": reference: dopri5 check " << number(d_dopri)
            << " m, rk4 check " << number(d_rk4) << " m, between " << number(d_between)
            << " m; using " << (dopri_wins ? "dopri5" : "rk4") << " (" << seconds(now() - started)
            << ")\n";
  return ref;
}

}  // namespace springlab::tradeoff
