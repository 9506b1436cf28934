// XPBD with small steps on the kit's fabric (issue 26): the three claims of "Small Steps in Physics
// Simulation" (Macklin et al. 2019) measured on the task 5 fabric without wind.
//   1. At equal cost, n substeps of one iteration against one step of n iterations: the largest
//      position error against the reference and the largest strain, on the lab's fabric and on
//      one a hundred times stiffer.
//   2. Against implicit Euler at the same frame budget (wall time a frame), the energy each keeps
//      on the fabric without dampers, where the exact motion keeps all of it.
//   3. The stiffness each method survives at that budget, symplectic Euler included.
// The frame is h_f = 0.02 s (two of the study's output intervals). Work is counted as passes over
// the springs (XPBD) and force evaluations; the budget of claims 2 and 3 is wall time, measured
// here beside the runs.
#include "measure.hpp"
#include "reference.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/errors.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace springlab::tradeoff {

namespace {

constexpr double frame = 0.02;  // s

// The largest (L − ℓ0)/ℓ0 over the springs.
double largest_strain(const std::vector<Spring>& springs, const Vectors& r) {
  double largest = 0.0;
  for (const Spring& s : springs)
    largest = std::max(largest, ((r.col(s.p) - r.col(s.q)).norm() - s.rest_length) / s.rest_length);
  return largest;
}

SceneParameters with(SceneParameters p, const std::string& method, double h, int substeps = 1,
                     int iterations = 1) {
  set_parameter(p, "integrator", method);
  set_number(p, "step", h);
  p.xpbd.substeps = substeps;
  p.xpbd.iterations = iterations;
  return p;
}

std::string label(const SceneParameters& p) {
  if (p.integrator == "xpbd")
    return "xpbd " + std::to_string(p.xpbd.substeps) + "×" + std::to_string(p.xpbd.iterations);
  return p.integrator + " h = " + number(p.step);
}

// One run, observed after every frame: against `reference` (output times every `sample` s, a
// whole number of frames) when it is given; the energy less `energy_floor`, divided by its start.
XpbdRun run_against(const SceneParameters& p, const Trajectory* reference, double duration,
                    double sample, double energy_floor = 0.0) {
  XpbdRun out;
  out.label = label(p);
  const long frames_a_sample = std::max(1L, std::lround(sample / frame));
  try {
    Simulation sim(p, lab_implementation());
    const long per = std::max(1L, std::lround(frame / p.step));
    const long frames = std::lround(duration / frame);
    const double start_energy = sim.diagnostics().total() - energy_floor;
    double busy = 0.0;
    for (long j = 0; j <= frames; ++j) {
      if (j > 0) {
        const double started = now();
        sim.advance(per);
        busy += now() - started;
      }
      const Vectors& r = sim.particles().position;
      out.strain = std::max(out.strain, largest_strain(sim.scene().springs, r));
      const auto k = std::size_t(j / frames_a_sample);
      if (reference && j % frames_a_sample == 0 && k < reference->position.size())
        out.error = std::max(out.error, position_error(r, reference->position[k]));
      out.time.push_back(double(j) * frame);
      const double kept = sim.diagnostics().total() - energy_floor;
      out.energy.push_back(start_energy != 0.0 ? kept / start_energy : kept);
    }
    sim.check();
    out.frame_seconds = busy / double(frames);
    out.projections = sim.integrator().solver_work().projections;
    out.evaluations = sim.force_evaluations();
  } catch (const DivergenceError& e) {
    out.stable = false;
    out.why = "diverged at t = " + number(e.time()) + " s";
  }
  return out;
}

// The smallest wall time a frame of p takes, over three runs of a few frames (s).
double frame_time(const SceneParameters& p) {
  double best = std::numeric_limits<double>::infinity();
  const long per = std::max(1L, std::lround(frame / p.step));
  try {
    Simulation sim(p, lab_implementation());
    sim.advance(per);  // start-up
    for (int round = 0; round < 3; ++round) {
      const double started = now();
      sim.advance(5 * per);
      best = std::min(best, (now() - started) / 5.0);
    }
  } catch (const DivergenceError&) {
  }
  return best;
}

}  // namespace

namespace {

// 1. n×1 against 1×n, on the lab fabric and on one a hundred times stiffer.
void substeps_against_iterations(XpbdStudy& study, const Scenario& fabric,
                                 const StudyOptions& options, Progress& progress) {
  const double duration = options.duration, sample = options.sample;
  const SceneParameters lab = fabric.params;
  study.stiff_factor = 100.0;
  SceneParameters stiff = lab;
  for (SpringFamilyParameters* family : {&stiff.structural, &stiff.shear, &stiff.bend})
    family->k *= study.stiff_factor;
  progress.begin("xpbd: the stiff fabric's reference (rk4 at h_lab/512 and h_lab/1024)");
  Scenario stiff_scene = fabric;
  stiff_scene.params = stiff;
  const Trajectory stiff_reference = rk4_trajectory(stiff_scene, lab.step / 512.0, options);
  const Trajectory stiff_check = rk4_trajectory(stiff_scene, lab.step / 1024.0, options);
  study.stiff_reference_error = largest_difference(stiff_reference, stiff_check);
  study.lab_reference_error = fabric.reference_error;
  for (const bool is_stiff : {false, true}) {
    const SceneParameters& p = is_stiff ? stiff : lab;
    const Trajectory& reference = is_stiff ? stiff_check : fabric.reference;
    const std::vector<Spring> springs = build_scene(p, lab_implementation()).springs;
    double strain = 0.0;
    for (const Vectors& r : reference.position)
      strain = std::max(strain, largest_strain(springs, r));
    (is_stiff ? study.stiff_reference_strain : study.lab_reference_strain) = strain;
    for (int n : {1, 2, 4, 8, 16, 32, 64}) {
      progress.begin("xpbd: " + std::string(is_stiff ? "stiff" : "lab") + " fabric, " +
                     std::to_string(n) + " substeps against " + std::to_string(n) + " iterations");
      XpbdPair pair;
      pair.stiff = is_stiff;
      pair.n = n;
      pair.substeps = run_against(with(p, "xpbd", frame, n, 1), &reference, duration, sample);
      pair.iterations = run_against(with(p, "xpbd", frame, 1, n), &reference, duration, sample);
      study.pairs.push_back(pair);
    }
  }
}

// The frame budget: implicit Euler's wall time a frame at h_f (one step) on the lab fabric; XPBD's
// substeps within it (one iteration each), and symplectic Euler's steps.
void frame_budget(XpbdStudy& study, const Scenario& fabric, Progress& progress) {
  const SceneParameters& lab = fabric.params;
  progress.begin("xpbd: the frame budget (implicit Euler's frame time)");
  study.budget_seconds = frame_time(with(lab, "implicit-euler", frame));
  study.evaluation_seconds = evaluation_time(fabric);
  study.budget_substeps = 1;
  for (int n = 2; n <= 256; n *= 2)
    if (frame_time(with(lab, "xpbd", frame, n, 1)) <= study.budget_seconds)
      study.budget_substeps = n;
  study.budget_symplectic_steps = 1;
  for (int n = 2; n <= 256; n *= 2)
    if (frame_time(with(lab, "symplectic-euler", frame / n)) <= study.budget_seconds)
      study.budget_symplectic_steps = n;
}

// 2. The energy kept, without dampers: (E − E_eq)/(E_0 − E_eq), E_eq the hanging equilibrium's
//    energy (the least the fabric can have), 1 for the exact motion.
void energy_kept(XpbdStudy& study, const SceneParameters& lab, const StudyOptions& options,
                 Progress& progress) {
  SceneParameters undamped = lab;
  for (SpringFamilyParameters* family : {&undamped.structural, &undamped.shear, &undamped.bend})
    family->b = 0.0;
  progress.begin("xpbd: energy kept without dampers");
  {
    const Equilibrium equilibrium = hanging_equilibrium(lab);
    Simulation probe(undamped, lab_implementation());
    const Vectors start = probe.particles().position;
    study.equilibrium_energy =
        total_energy(probe, equilibrium.scene.particles.position,
                     Vectors::Zero(2, equilibrium.scene.particles.size()), start);
  }
  const int n = study.budget_substeps, m = study.budget_symplectic_steps;
  for (const SceneParameters& p :
       {with(undamped, "rk4", frame / 64), with(undamped, "implicit-euler", frame),
        with(undamped, "xpbd", frame, n, 1), with(undamped, "xpbd", frame, 1, n),
        with(undamped, "symplectic-euler", frame / m)})
    study.energy.push_back(
        run_against(p, nullptr, options.duration, options.sample, study.equilibrium_energy));
}

// 3. The stiffness each survives at the budget.
void stiffness_survived(XpbdStudy& study, const SceneParameters& lab, const StudyOptions& options,
                        Progress& progress) {
  const int n = study.budget_substeps, m = study.budget_symplectic_steps;
  for (double factor : {1.0, 10.0, 100.0, 1e3, 1e4, 1e5}) {
    progress.begin("xpbd: stiffness x" + number(factor) + " at the frame budget");
    SceneParameters p = lab;
    for (SpringFamilyParameters* family : {&p.structural, &p.shear, &p.bend})
      family->k *= factor;
    XpbdStiffness row;
    row.factor = factor;
    for (const SceneParameters& q :
         {with(p, "symplectic-euler", frame / m), with(p, "implicit-euler", frame),
          with(p, "xpbd", frame, n, 1), with(p, "xpbd", frame, 1, n)})
      row.runs.push_back(run_against(q, nullptr, options.duration, options.sample));
    study.stiffness.push_back(row);
  }
}

}  // namespace

XpbdStudy xpbd_study(const Scenario& fabric, const StudyOptions& options, Progress& progress) {
  XpbdStudy study;
  study.frame = frame;
  study.duration = options.duration;
  substeps_against_iterations(study, fabric, options, progress);
  frame_budget(study, fabric, progress);
  energy_kept(study, fabric.params, options, progress);
  stiffness_survived(study, fabric.params, options, progress);
  progress.done(0.0);
  return study;
}

namespace {

std::string pass(const XpbdRun& run) {
  return run.stable ? number(run.error, 3) : "**" + run.why + "**";
}

// The section's opening: what XPBD is, the paper's claims, what was measured where.
void write_xpbd_intro(std::ostream& out, const XpbdStudy& x, const std::string& machine) {
  out << "\n## XPBD with small steps, measured on the kit's fabric\n\n"
      << "XPBD (`--integrator xpbd`, handout/integrators.md) projects every spring as a distance "
         "constraint of compliance 1/k, with its damper as the constraint's damping term, in "
         "`xpbd.substeps` substeps of `xpbd.iterations` Gauss–Seidel passes over the springs. "
         "Macklin et al. (\"Small Steps in Physics Simulation\", SCA 2019) report three things; "
         "here each is measured on the task 5 fabric without wind (20×20, gravity, top row "
         "pinned), a frame of h_f = "
      << number(x.frame) << " s, " << number(x.duration) << " s of motion"
      << (machine.empty() ? "" : ", on " + machine) << ".\n\n";
}

// 1. n substeps of one iteration against one step of n iterations: the table.
void write_substeps_table(std::ostream& out, const XpbdStudy& x, const std::string& figures) {
  out << "### 1. n substeps of one iteration against one step of n iterations\n\n"
      << "Equal work: both make n passes over the springs a frame (counted: the projections "
         "below). Error: the largest distance to the reference at the output times "
         "(lab fabric: the study's reference, error ≤ "
      << number(x.lab_reference_error) << " m; stiff fabric, k × " << number(x.stiff_factor)
      << ": the kit's rk4 at h_lab/1024, which differs from h_lab/512 by "
      << number(x.stiff_reference_error)
      << " m). Strain: the largest (L − ℓ0)/ℓ0 over the springs and the run; the reference's is "
      << number(x.lab_reference_strain, 4) << " (lab) and " << number(x.stiff_reference_strain, 4)
      << " (stiff).\n\n"
      << "![xpbd substeps against iterations](" << figures
      << "/xpbd-substeps-vs-iterations.svg)\n\n"
      << "| fabric | n | error n×1 (m) | error 1×n (m) | strain n×1 | strain 1×n | ms a frame "
         "n×1 | ms a frame 1×n | projections a frame |\n"
      << "|---|---|---|---|---|---|---|---|---|\n";
  for (const XpbdPair& p : x.pairs) {
    const double frames = std::max(1.0, double(p.substeps.time.size()) - 1.0);
    out << "| " << (p.stiff ? "stiff" : "lab") << " | " << p.n << " | " << pass(p.substeps) << " | "
        << pass(p.iterations) << " | " << number(p.substeps.strain, 4) << " | "
        << number(p.iterations.strain, 4) << " | " << number(1e3 * p.substeps.frame_seconds, 3)
        << " | " << number(1e3 * p.iterations.frame_seconds, 3) << " | "
        << number(double(p.substeps.projections) / frames, 6) << " |\n";
  }
}

// 1. What the table says of the paper's claim, on accuracy and on stretch.
void write_substeps_verdict(std::ostream& out, const XpbdStudy& x) {
  // Accuracy: which of each pair n > 1 had the smaller position error. Stretch, the paper's
  // measure: which stretched less, and which came closer to the reference's own stretch.
  int substeps_win = 0, pairs = 0, less_stretch = 0, closer_stretch = 0;
  for (const XpbdPair& p : x.pairs)
    if (p.n > 1 && p.substeps.stable && p.iterations.stable) {
      ++pairs;
      if (p.substeps.error < p.iterations.error) ++substeps_win;
      const double reference = p.stiff ? x.stiff_reference_strain : x.lab_reference_strain;
      if (p.substeps.strain < p.iterations.strain) ++less_stretch;
      if (std::abs(p.substeps.strain - reference) < std::abs(p.iterations.strain - reference))
        ++closer_stretch;
    }
  out << "\nThe paper: 30 substeps × 1 iteration (13.5 ms a frame) stretch much less than 1 × 30 "
         "(12.4 ms). Here, at equal passes over the springs, n×1 had the smaller position error "
         "in "
      << substeps_win << " of " << pairs << " pairs with n > 1"
      << (substeps_win == pairs ? ": on accuracy the kit's figures agree with the paper."
          : substeps_win == 0   ? ": on accuracy the kit's figures do not agree with the paper."
                                : ": on accuracy the kit's figures agree with the paper in part.")
      << " On stretch they "
      << (less_stretch == pairs ? "agree"
          : less_stretch == 0   ? "do not agree"
                                : "agree only in part")
      << ": n×1 stretched less than 1×n in " << less_stretch << " of " << pairs
      << " pairs, and its largest strain was the closer to the reference's in " << closer_stretch
      << " of them. On this fabric the stretch is physical (the reference's own largest strain is "
      << number(x.lab_reference_strain, 3) << " on the lab fabric, "
      << number(x.stiff_reference_strain, 3)
      << " on the stiff one), not only a constraint error as on the paper's nearly inextensible "
         "cloth; one step of n iterations, which converges to backward Euler at the whole frame, "
         "damps the falling fabric's swing and so stretches less than the true motion does.\n";
}

// 2. Energy kept against implicit Euler at the same frame budget.
void write_energy_section(std::ostream& out, const XpbdStudy& x, const std::string& figures) {
  out << "\n### 2. Energy kept against implicit Euler at the same frame budget\n\n"
      << "The budget: implicit Euler's wall time for one frame (one step of h_f) on the lab "
         "fabric, "
      << number(1e3 * x.budget_seconds, 3) << " ms ("
      << number(x.budget_seconds / x.evaluation_seconds, 3)
      << " force evaluations' time). Within it fit " << x.budget_substeps
      << " XPBD substeps of one iteration and " << x.budget_symplectic_steps
      << " symplectic Euler steps. Without dampers the exact motion keeps its energy; shown is "
         "(E − E_eq)/(E_0 − E_eq), E_eq the energy at the hanging equilibrium (the least there "
         "is), so 1 is all of it kept and 0 all of it damped away.\n\n"
      << "![xpbd energy](" << figures << "/xpbd-energy.svg)\n\n"
      << "| method | energy kept at the end | least over the run | ms a frame "
         "|\n|---|---|---|---|\n";
  for (const XpbdRun& r : x.energy) {
    double least = 1e300;
    for (double e : r.energy)
      least = std::min(least, e);
    out << "| " << r.label << " | "
        << (r.stable ? number(r.energy.empty() ? 0.0 : r.energy.back(), 3) : "**" + r.why + "**")
        << " | " << (r.stable ? number(least, 3) : "") << " | " << number(1e3 * r.frame_seconds, 3)
        << " |\n";
  }
  const auto find = [&](const std::string& prefix) -> const XpbdRun* {
    for (const XpbdRun& r : x.energy)
      if (r.label.rfind(prefix, 0) == 0) return &r;
    return nullptr;
  };
  const XpbdRun* ie = find("implicit-euler");
  const XpbdRun* xs = find("xpbd " + std::to_string(x.budget_substeps) + "×1");
  if (ie && xs && ie->stable && xs->stable && !ie->energy.empty() && !xs->energy.empty())
    out << "\nThe paper: small substeps damp less than implicit Euler with large steps. Here XPBD "
        << x.budget_substeps << "×1 kept " << number(xs->energy.back(), 3)
        << " of the energy, implicit Euler at h_f " << number(ie->energy.back(), 3) << ": "
        << (xs->energy.back() > ie->energy.back() ? "the kit's figures agree."
                                                  : "the kit's figures do not agree.")
        << "\n";
}

// 3. The stiffness each survives at that budget: the table.
void write_stiffness_table(std::ostream& out, const XpbdStudy& x) {
  out << "\n### 3. The stiffness each survives at that budget\n\n"
      << "Every family's k multiplied by the factor, the lab's dampers kept; each method within "
         "the frame budget above. A cell gives the largest strain of a run that stayed stable, "
         "or when it diverged.\n\n| k × | ";
  if (!x.stiffness.empty()) {
    for (const XpbdRun& r : x.stiffness.front().runs)
      out << r.label << " | ";
    out << "\n|---|";
    for (std::size_t i = 0; i < x.stiffness.front().runs.size(); ++i)
      out << "---|";
    out << "\n";
  }
  for (const XpbdStiffness& row : x.stiffness) {
    out << "| " << number(row.factor) << " | ";
    for (const XpbdRun& r : row.runs)
      out << (r.stable ? "strain " + number(r.strain, 3) : "**" + r.why + "**") << " | ";
    out << "\n";
  }
}

// 3. The largest factor each method survived, and what surviving means at the stiffest.
void write_stiffness_survival(std::ostream& out, const XpbdStudy& x) {
  // Survival per method: the largest factor it ran.
  if (!x.stiffness.empty()) {
    out << "\nThe largest stiffness factor each survived: ";
    for (std::size_t i = 0; i < x.stiffness.front().runs.size(); ++i) {
      double survived = 0.0;
      for (const XpbdStiffness& row : x.stiffness)
        if (row.runs[i].stable) survived = row.factor;
      out << (i ? "; " : "") << x.stiffness.front().runs[i].label << ": "
          << (survived > 0 ? "× " + number(survived) : "none");
    }
    out << ". The paper: XPBD with small steps stays stable where explicit methods fail. Here "
           "symplectic Euler, an explicit method, fails once h_f/"
        << x.budget_symplectic_steps
        << " exceeds its critical step, which falls as 1/√k; implicit Euler and XPBD treat the "
           "springs implicitly and have no such limit: the kit's figures agree.";
    // What surviving means: the stretch left at the stiffest factor.
    const XpbdStiffness& stiffest = x.stiffness.back();
    const XpbdRun* implicit = nullptr;
    const XpbdRun* substeps = nullptr;
    for (const XpbdRun& r : stiffest.runs) {
      if (r.label.rfind("implicit-euler", 0) == 0) implicit = &r;
      if (r.label == "xpbd " + std::to_string(x.budget_substeps) + "×1") substeps = &r;
    }
    if (implicit && substeps && implicit->stable && substeps->stable)
      out << " Stable is not converged, though: at k × " << number(stiffest.factor) << " XPBD "
          << x.budget_substeps << "×1 left a largest strain of " << number(substeps->strain, 3)
          << ", implicit Euler " << number(implicit->strain, 3)
          << " (a stiffer spring stretches less under the same weight); at this budget XPBD's "
             "passes do not finish what they start on stiff springs, and what is left shows as "
             "stretch.";
    out << "\n";
  }
}

}  // namespace

void write_xpbd_section(std::ostream& out, const XpbdStudy& x, const std::string& figures,
                        const std::string& machine) {
  write_xpbd_intro(out, x, machine);
  write_substeps_table(out, x, figures);
  write_substeps_verdict(out, x);
  write_energy_section(out, x, figures);
  write_stiffness_table(out, x);
  write_stiffness_survival(out, x);
}

std::string write_xpbd_figures(const XpbdStudy& x, const std::string& dir,
                               const std::string& figures) {
  namespace fs = std::filesystem;
  const fs::path data = fs::path(dir) / "xpbd-substeps.dat";
  {
    std::ofstream out(data);
    out.precision(8);
    for (const bool stiff : {false, true}) {
      out << "# " << (stiff ? "stiff" : "lab") << ": n error_substeps error_iterations\n";
      for (const XpbdPair& p : x.pairs)
        if (p.stiff == stiff)
          out << p.n << ' ' << (p.substeps.stable ? p.substeps.error : std::nan("")) << ' '
              << (p.iterations.stable ? p.iterations.error : std::nan("")) << '\n';
      out << "\n\n";
    }
  }
  const fs::path energy = fs::path(dir) / "xpbd-energy.dat";
  {
    std::ofstream out(energy);
    out.precision(8);
    for (const XpbdRun& r : x.energy) {
      out << "# " << r.label << "\n";
      for (std::size_t j = 0; j < r.energy.size(); ++j)
        out << r.time[j] << ' ' << r.energy[j] << '\n';
      out << "\n\n";
    }
  }
  const std::string svg1 = (fs::path(figures) / "xpbd-substeps-vs-iterations.svg").string();
  const std::string svg2 = (fs::path(figures) / "xpbd-energy.svg").string();
  std::string script =
      "set terminal svg size 760,560 dynamic font 'DejaVu Sans,12'\nset output '" + svg1 +
      "'\nset title 'XPBD on the fabric: n substeps x 1 iteration against 1 step x n "
      "iterations'\nset key inside left bottom font ',10'\nset grid\nset logscale xy\nset "
      "format y '10^{%L}'\nset xlabel 'n (passes over the springs a frame of " +
      number(x.frame) + " s)'\nset ylabel 'largest position error (m)'\nplot '" + data.string() +
      "' index 0 using 1:2 with linespoints lc 1 title 'lab fabric, n x 1', '' index 0 using "
      "1:3 with linespoints lc 1 dt 2 title 'lab fabric, 1 x n', '' index 1 using 1:2 with "
      "linespoints lc 2 title 'stiff fabric (k x " +
      number(x.stiff_factor) +
      "), n x 1', '' index 1 using 1:3 with linespoints lc 2 dt 2 title 'stiff fabric, 1 x n'\n"
      "reset\n";
  script += "set terminal svg size 760,560 dynamic font 'DejaVu Sans,12'\nset output '" + svg2 +
            "'\nset title 'Energy kept without dampers, (E - E_eq)/(E_0 - E_eq), at the frame "
            "budget'\nset key inside right bottom font ',10'\nset grid\nset xlabel 't (s)'\nset "
            "ylabel 'energy kept'\nset yrange [0:1.3]\nplot";
  for (std::size_t i = 0; i < x.energy.size(); ++i)
    script += std::string(i ? "," : "") + " '" + energy.string() + "' index " + std::to_string(i) +
              " with lines lw " + (i == 0 ? "5 lc 'gray70'" : "1.5") + " title '" +
              x.energy[i].label + (i == 0 ? " (reference)" : "") + "'";
  return script + "\nreset\n";
}

}  // namespace springlab::tradeoff
