// Task 4's damped scene in the study: where task 4's central-difference Verlet is worth its extra
// evaluations. Textbook Verlet (the velocity in the dampers from the backward difference) has
// symplectic Euler's positions, so its limit is 2(√(1 + ζ²) − ζ)/ω per mode; the lab's is 2/ω_max
// whatever the damping, until its iteration's factor h c/2 nears 0.76. The scene's step lies
// between the two.
#include "measure.hpp"
#include "springlab/eigen_solvers.hpp"
#include "springlab/errors.hpp"
#include "springlab/scene.hpp"
#include "springlab/stability.hpp"
#include "textbook_verlet.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

namespace springlab::tradeoff {

namespace {

DampedRun run_damped(const SceneParameters& p, const std::string& method,
                     const Implementation& impl) {
  DampedRun run;
  run.method = method;
  try {
    Simulation sim(p, impl);
    const long steps = std::lround(p.duration / p.step);
    run.time.push_back(0.0);
    run.energy.push_back(sim.diagnostics().total());
    try {
      for (long n = 0; n < steps; ++n) {
        sim.step();
        run.time.push_back(sim.time());
        run.energy.push_back(sim.diagnostics().total());
      }
      sim.check();
    } catch (const DivergenceError& e) {
      run.stable = false;
      run.why = "diverged at t = " + number(e.time()) + " s";
    }
    if (sim.steps_taken() > 0)
      run.evaluations_a_step = double(sim.force_evaluations()) / double(sim.steps_taken());
  } catch (const std::exception& e) {  // the student's task 4 is not written yet
    run.stable = false;
    run.why = e.what();
  }
  return run;
}

}  // namespace

DampedScene damped_scene(const StudyOptions& options) {
  DampedScene d;
  const SceneParameters p = load_scene("task4-damped");
  d.h = p.step;
  const LinearModel model = linearise_at_rest(p, lab_implementation());
  d.textbook_limit = critical_step(model, "symplectic-euler");
  d.verlet_limit = verlet_critical_step(model);
  d.iteration_limit = verlet_iteration_limit(model);
  // The fastest mode and its damping ratio: ψ from M^-½ K M^-½, c = ψᵀ M^-½ C M^-½ ψ.
  const Eigen::VectorXd scale = model.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd k = scale.asDiagonal() * model.stiffness * scale.asDiagonal();
  const Eigen::MatrixXd c = scale.asDiagonal() * model.damping * scale.asDiagonal();
  const solvers::SymmetricEigen modes = solvers::symmetric_eigen(k);
  const Eigen::Index top = modes.eigenvalues().size() - 1;
  d.omega_max = std::sqrt(modes.eigenvalues()[top]);
  const Eigen::VectorXd psi = modes.eigenvectors().col(top);
  d.zeta = psi.dot(c * psi) / (2.0 * d.omega_max);
  d.runs.push_back(run_damped(p, "verlet", lab_implementation()));
  d.runs.push_back(
      run_damped(p, "textbook-verlet", textbook_verlet_implementation(lab_implementation())));
  if (options.student)
    d.runs.push_back(run_damped(p, yours + "verlet", implementation_of(yours + "verlet")));
  return d;
}

void write_damped_section(std::ostream& out, const DampedScene& d, const std::string& figures) {
  out << "\n## Task 4's damped scene: where the lab's Verlet pays\n\n"
      << "Scene `task4-damped` (`./lab view task4-damped`): the 3×3 grid of task 4 with every "
         "damper four times the lab's (b = 0.4 and 0.2 N·s/m) at h = "
      << number(d.h) << " s. Its fastest mode has ω_max = " << number(d.omega_max, 4)
      << " rad/s and damping ratio ζ = " << number(d.zeta, 3)
      << ". Textbook Verlet (the dampers see the backward difference (r_n − r_{n−1})/h) has "
         "symplectic Euler's positions, so its limit is symplectic Euler's, 2(√(1 + ζ²) − ζ)/ω "
         "per mode: "
      << number(d.textbook_limit, 4) << " s on this scene (exact, by bisection of the step "
      << "matrix). Task 4's Verlet keeps 2/ω_max = " << number(d.verlet_limit, 4)
      << " s whatever the damping (its iteration settles in time below "
      << number(d.iteration_limit, 4) << " s). The scene's h = " << number(d.h)
      << " s lies between them.\n\n"
      << "![task4-damped energy](" << figures << "/task4-damped-energy.svg)\n\n"
      << "| method | outcome over "
      << number(d.runs.empty() || d.runs.front().time.empty() ? 0.0 : d.runs.front().time.back())
      << " s | energy at the end (J) | evaluations a step |\n|---|---|---|---|\n";
  for (const DampedRun& r : d.runs)
    out << "| `" << shown(r.method) << "` | "
        << (r.stable ? "ran, calmed down" : "**" + r.why + "**") << " | "
        << (r.stable && !r.energy.empty() ? number(r.energy.back()) : "") << " | "
        << number(r.evaluations_a_step, 3) << " |\n";
  out << "\nSo the repetition of (4.1)–(4.2) costs several evaluations a step, and it buys a "
         "step this scene's dampers would not otherwise allow.\n";
}

std::string write_damped_figure(const DampedScene& d, const std::string& dir,
                                const std::string& figures) {
  namespace fs = std::filesystem;
  const fs::path data = fs::path(dir) / "task4-damped-energy.dat";
  std::ofstream out(data);
  out.precision(8);
  for (const DampedRun& r : d.runs) {
    out << "# " << shown(r.method) << "\n";
    for (std::size_t j = 0; j < r.energy.size(); ++j)
      if (std::isfinite(r.energy[j]) && r.energy[j] > 0)
        out << r.time[j] << ' ' << r.energy[j] << '\n';
    out << "\n\n";
  }
  const std::string svg = (fs::path(figures) / "task4-damped-energy.svg").string();
  std::string script =
      "set terminal svg size 760,560 dynamic font 'DejaVu Sans,12'\nset output '" + svg +
      "'\nset title 'task4-damped: total energy at h = " + number(d.h) +
      " s'\nset key inside right top font ',10'\nset grid\nset logscale y\nset format y "
      "'10^{%L}'\nset xlabel 't (s)'\nset ylabel 'kinetic + spring energy (J)'\nplot";
  for (std::size_t i = 0; i < d.runs.size(); ++i)
    script += std::string(i ? "," : "") + " '" + data.string() + "' index " + std::to_string(i) +
              " with lines lw 2 title '" + shown(d.runs[i].method) + "'";
  return script + "\nreset\n";
}

}  // namespace springlab::tradeoff
