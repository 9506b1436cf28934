// The runner's CSV: a header row, then one row per output step, into a file or standard output.
// A row that cannot be written (a full disk, a closed pipe) stops the run: no silent loss.
#pragma once

#include "springlab/simulation.hpp"

#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>

namespace springlab {

/// t, then x{i},y{i},vx{i},vy{i} for every particle i (0-based), then kinetic,potential,px,py
/// (potential: springs and gravity together, as in the summary and the viewer's plot).
void write_csv_header(std::ostream& out, int particles);

/// One row for the simulation's current state; numbers in the shortest form that reads back
/// exactly.
void write_csv_row(std::ostream& out, const Simulation& simulation);

/// Output that could not be written; says where, why and how far the run got.
class WriteFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The CSV of one run: `path` is a file or "-" for standard output.
class CsvOutput {
 public:
  /// Opens the file (throws InvalidParameter naming --csv if it cannot be created).
  explicit CsvOutput(const std::string& path);
  bool to_stdout() const;
  /// The header and the first row; then row() after each written step.
  void start(const Simulation& simulation);
  /// Throws WriteFailed if this or an earlier row could not be written.
  void row(const Simulation& simulation);
  /// Flushes and closes; throws WriteFailed if anything was lost.
  void finish(const Simulation& simulation);

 private:
  void check(const Simulation& simulation);

  std::ofstream file_;
  std::ostream* stream_;
  std::string shown_;  // "\"run.csv\"" or "standard output"
  long rows_ = 0;
};

}  // namespace springlab
