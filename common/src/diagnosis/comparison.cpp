#include "springlab/comparison.hpp"
#include "support/numbers.hpp"

#include "springlab/errors.hpp"
#include "springlab/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

namespace springlab {
namespace {

using internal::significant;

double per_step(const RunRecord& r) {
  return r.steps > 0 ? double(r.evaluations) / double(r.steps) : 0.0;
}

// "1 force evaluation", "4.6 force evaluations"
std::string evaluations(const RunRecord& r) {
  const double n = per_step(r);
  return significant(n) + (n == 1.0 ? " force evaluation" : " force evaluations");
}

// What is worth a remark: a difference well above what rounding and the order of sums give two
// correct codes (measured: below 1e-9 of the energy and 1e-10 m on the lab's scenes).
constexpr double energy_share = 0.1;       // of the energy's scale
constexpr double evaluation_share = 0.05;  // of the reference's evaluations a step
constexpr double distance_share = 0.01;    // of the grid spacing

}  // namespace

RunRecord record_of(const Simulation& sim, double start_energy) {
  RunRecord r;
  r.start_energy = start_energy;
  r.end_energy = sim.diagnostics().total();
  r.steps = sim.steps_taken();
  r.evaluations = sim.force_evaluations();
  r.position = sim.particles().position;
  return r;
}

Comparison compare_runs(const SceneParameters& p, const RunRecord& yours,
                        const RunRecord& reference) {
  Comparison c;
  c.yours = yours;
  c.reference = reference;
  c.spacing = p.spacing > 0 ? p.spacing : 1.0;
  if (yours.position.cols() == reference.position.cols() && yours.position.cols() > 0)
    c.distance = (yours.position - reference.position).colwise().norm().maxCoeff();
  else
    c.distance = std::nan("");

  std::vector<std::string> facts;
  const double change_yours = yours.end_energy - yours.start_energy;
  const double change_reference = reference.end_energy - reference.start_energy;
  const double scale = std::max({std::abs(reference.start_energy), std::abs(reference.end_energy),
                                 std::abs(change_reference), 1e-12});
  const bool rises = change_reference > energy_share * scale;
  const bool falls = change_reference < -energy_share * scale;
  // Yours measured on its own scale: a run that loses most of its own energy falls, whatever the
  // reference gained.
  const double own_scale =
      std::max({std::abs(yours.start_energy), std::abs(yours.end_energy), 1e-12});
  if ((rises && change_yours < -energy_share * own_scale) ||
      (falls && change_yours > energy_share * own_scale)) {
    facts.push_back("your energy " + std::string(change_yours < 0 ? "falls" : "rises") + " from " +
                    significant(yours.start_energy) + " J to " + significant(yours.end_energy) +
                    " J where the reference's " + (rises ? "rises" : "falls") + " to " +
                    significant(reference.end_energy) + " J");
  } else if (std::abs(yours.end_energy - reference.end_energy) > energy_share * scale) {
    std::string ratio;
    if (yours.end_energy * reference.end_energy > 0 &&
        std::abs(yours.end_energy) > 2 * std::abs(reference.end_energy))
      ratio = ", " + significant(yours.end_energy / reference.end_energy) + " times";
    facts.push_back("your energy ends at " + significant(yours.end_energy) + " J" + ratio +
                    (ratio.empty() ? " where the reference's ends at " : " the reference's ") +
                    significant(reference.end_energy) + " J");
  }
  const double mine = per_step(yours), theirs = per_step(reference);
  if (std::abs(mine - theirs) > evaluation_share * std::max(theirs, 1.0)) {
    std::string why;
    if (mine < theirs && p.integrator == "verlet")
      why = ": with dampers the reference repeats (4.1)-(4.2) until the velocity settles";
    facts.push_back("your code evaluates the forces " + significant(mine) +
                    " times a step, the reference " + significant(theirs) + why);
  }
  if (c.distance > distance_share * c.spacing)
    facts.push_back("your run ends " + significant(c.distance) + " m (" +
                    significant(c.distance / c.spacing) + " grid spacings) from the reference's");
  for (std::size_t i = 0; i < facts.size(); ++i)
    c.remark += (i == 0 ? "unlike the reference: " : "; ") + facts[i];
  return c;
}

std::optional<Comparison> compare_with_reference(const SceneParameters& p, const RunRecord& yours,
                                                 const Implementation& kit) {
  try {
    DivergenceLimits quiet;  // only whether and when it diverges: no diagnosis of it
    quiet.diagnose = false;
    Simulation reference(p, kit, quiet);
    const double start = reference.diagnostics().total();
    try {
      reference.advance(yours.steps);
      reference.check();
    } catch (const DivergenceError& error) {
      // The method itself diverges on this scene at this h (explicit Euler beyond its critical
      // step, say) and your run did not: a fact worth saying, with your run's energy beside it.
      Comparison c;
      c.yours = yours;
      c.reference.start_energy = start;
      c.reference.steps = reference.steps_taken();
      c.reference.evaluations = reference.force_evaluations();
      c.spacing = p.spacing > 0 ? p.spacing : 1.0;
      c.distance = std::nan("");
      c.reference_diverged_at = error.time();
      const double change = yours.end_energy - yours.start_energy;
      c.remark =
          "unlike the reference: the reference's code diverges on this scene at this h "
          "(t = " +
          significant(error.time()) + " s), and your run does not: your energy " +
          (change < 0 ? "falls" : "rises") + " from " + significant(yours.start_energy) + " J to " +
          significant(yours.end_energy) + " J in " + std::to_string(yours.steps) + " steps";
      return c;
    }
    return compare_runs(p, yours, record_of(reference, start));
  } catch (const std::exception&) {
    return std::nullopt;  // the reference failed here: nothing to compare with
  }
}

std::string comparison_figures(const Comparison& c) {
  std::ostringstream out;
  if (!std::isnan(c.reference_diverged_at)) {
    out << "ends with energy " << significant(c.yours.end_energy)
        << " J; the reference's run diverged "
        << "at t = " << significant(c.reference_diverged_at) << " s; " << evaluations(c.yours)
        << " a step (the reference's " << significant(per_step(c.reference)) << ")";
    return out.str();
  }
  out << "ends " << significant(c.distance) << " m from the reference's run; energy "
      << significant(c.yours.end_energy) << " J (the reference's "
      << significant(c.reference.end_energy) << " J); " << evaluations(c.yours)
      << " a step (the reference's " << significant(per_step(c.reference)) << ")";
  return out.str();
}

}  // namespace springlab
