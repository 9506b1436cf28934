// A run of the student's code set beside the reference's on the same scene, h and number of
// steps, where neither diverged: how far apart they end and what the difference shows. Shared by
// the runner's summary and the viewer's panel, so both say the same. The remark states measured
// facts (energies, force evaluations per step, distance); it names no mistake it cannot see.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace springlab {

class Simulation;
struct Implementation;

/// What a finished run is compared by.
struct RunRecord {
  double start_energy = 0.0;  ///< total energy at the start, J
  double end_energy = 0.0;    ///< total energy at the end, J
  long steps = 0;             ///< steps taken
  long evaluations = 0;       ///< force evaluations made
  Vectors position;           ///< every particle's position at the end, m
};

/// sim's record now; start_energy as measured before its first step, J.
RunRecord record_of(const Simulation& sim, double start_energy);

struct Comparison {
  RunRecord yours, reference;
  double distance = 0.0;  ///< the largest |r_i - r_i(reference)| at the end, m
  double spacing = 1.0;   ///< the grid spacing, m: the scale the distance is judged on
  /// One line, "" when the runs agree: what differs, with figures (comparison.cpp says when).
  std::string remark;
  /// When the reference's run diverged (and yours did not): its time, s; NaN otherwise.
  double reference_diverged_at = std::nan("");
};

/// The two records compared (same scene and steps).
Comparison compare_runs(const SceneParameters& p, const RunRecord& yours,
                        const RunRecord& reference);

/// Runs `reference` (the kit's reference code) on p for yours.steps steps and compares; when the
/// reference diverges there (and so yours, which finished, did not), says that with your energy;
/// nothing when it fails otherwise.
std::optional<Comparison> compare_with_reference(const SceneParameters& p, const RunRecord& yours,
                                                 const Implementation& reference);

/// "ends 0.00212 m from the reference's run; energy -12.3 J (the reference's -12.3 J); 1 force
/// evaluation a step (the reference's 4.6)": the figures, always.
std::string comparison_figures(const Comparison& c);

}  // namespace springlab
