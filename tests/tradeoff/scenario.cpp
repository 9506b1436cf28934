// The three scenes of the study and the two-mass exact solution (handout section 1,
// /work notes: u'' = -(2k/m) u - (2b/m) u').
#include "measure.hpp"
#include "reference.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/errors.hpp"
#include "springlab/scene.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>

namespace springlab::tradeoff {

const Implementation& lab_implementation() {
  return implementation();  // this target is compiled in the reference namespace
}

bool is_students(const std::string& method) {
  return method.rfind(yours, 0) == 0;
}

std::string integrator_of(const std::string& method) {
  return is_students(method) ? method.substr(yours.size()) : method;
}

std::string shown(const std::string& method) {
  return is_students(method) ? integrator_of(method) + " (yours)" : method;
}

std::string not_written(const std::string& method) {
  if (!is_students(method)) return "";
  SceneParameters p = task_scene(1);
  p.integrator = integrator_of(method);
  try {
    Simulation sim(p, implementation_of(method));
    sim.step();
  } catch (const NotImplemented& e) {
    return e.what();
  } catch (const std::exception&) {  // written, and wrong: the runs will show how
  }
  return "";
}

const Implementation& implementation_of(const std::string& method) {
  if (!is_students(method)) return lab_implementation();
  return student_implementation(integrator_of(method) == "verlet" ? 4 : 1);
}

double position_error(const Vectors& r, const Vectors& r_ref) {
  return (r - r_ref).colwise().norm().maxCoeff();
}

double total_energy(const Simulation& sim, const Vectors& r, const Vectors& v,
                    const Vectors& start) {
  Particles state = sim.particles();
  state.position = r;
  state.velocity = v;
  const SceneParameters& p = sim.parameters();
  const Vec2 g = p.gravity.enabled ? p.gravity.acceleration : Vec2::Zero();
  return diagnose(state, sim.scene().springs, g, start).total();
}

long steps_between_samples(double sample, double h) {
  return std::max(1L, std::lround(sample / h));
}

namespace {

// Two equal masses released from rest with stretch u0 along the spring: the stretch is a damped
// oscillator u'' = -ω² u - c u', ω² = 2k/m, c = 2b/m, and the centre of mass stays put.
Trajectory two_mass_exact(const SceneParameters& p, const StudyOptions& options) {
  const double u0 = p.displacement.x(), l0 = p.structural.rest_length, m = p.mass;
  const double k = p.structural.k, omega2 = 2.0 * k / m, c = 2.0 * p.structural.b / m;
  const double wd = std::sqrt(omega2 - c * c / 4.0);
  const double centre = (p.spacing + u0) / 2.0;
  Trajectory exact;
  const long samples = std::lround(options.duration / options.sample);
  for (long j = 0; j <= samples; ++j) {
    const double t = double(j) * options.sample, decay = std::exp(-c * t / 2.0);
    const double u = decay * (u0 * std::cos(wd * t) + c * u0 / (2.0 * wd) * std::sin(wd * t));
    const double du = -decay * u0 * omega2 / wd * std::sin(wd * t);
    Vectors r(2, 2);
    r << centre - (l0 + u) / 2.0, centre + (l0 + u) / 2.0, 0.0, 0.0;
    exact.time.push_back(t);
    exact.position.push_back(r);
    exact.energy.push_back(m * du * du / 4.0 + k * u * u / 2.0);  // 2·½m(u'/2)² + ½ku²
  }
  return exact;
}

}  // namespace

Scenario make_scenario(const std::string& name, const StudyOptions& options) {
  Scenario s;
  s.name = name;
  if (name == "two-masses") {
    s.title = "two masses (task 1 scene)";
    s.params = task_scene(1);
  } else if (name == "grid") {
    s.title = "3x3 grid (task 4 scene)";
    s.params = task_scene(4);
  } else if (name == "fabric") {
    s.title = "20x20 fabric, gravity, top row pinned, no wind (task 5 scene)";
    s.params = task_scene(5);
    // Wind gusts make the model depend on t; without them every method sees one autonomous ODE.
    set_parameter(s.params, "wind.enabled", "false");
  } else {
    throw InvalidParameter("--scenes", "\"" + name + "\"", "two-masses, grid or fabric");
  }
  set_number(s.params, "duration", options.duration);
  if (name == "two-masses") {
    s.reference = two_mass_exact(s.params, options);
    s.reference_note = "the exact solution (handout section 1)";
    s.reference_error = 0.0;
  } else {
    ComputedReference computed = compute_reference(s, options);
    s.reference = std::move(computed.trajectory);
    s.reference_note = computed.note;
    s.reference_error = computed.error;
  }
  for (const double e : s.reference.energy)
    s.energy_scale = std::max(s.energy_scale, std::abs(e));
  return s;
}

}  // namespace springlab::tradeoff
