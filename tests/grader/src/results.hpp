// The results folder (--out) across runs. Each submission's folder holds its reports and a marker,
// .springlab-graded: its name, the signature of what was graded (its files, the kit's programs,
// the points and the limits) and its points per task. The gradebook and review.csv are made
// from every marker in the folder: grading a late submission into a class's folder replaces its
// row and keeps everyone else's, and a run that was interrupted, started again, grades only what
// it had not finished (a submission whose marker has the same signature is kept as it is).
#pragma once

#include "grading.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace springlab::grader {

/// What a submission's marker says.
struct Recorded {
  std::string name;                                ///< the submission's name (its gradebook row)
  std::string signature;                           ///< of what was graded
  std::map<int, double> points, max_points;        ///< per task
  std::map<int, std::string> faults;               ///< per task not graded: why
  std::map<int, std::vector<std::string>> review;  ///< per task: calls no task needs
};

class ResultsFolder {
 public:
  /// Takes `out` for this run: made if missing, refused (UsageError) when it holds files the
  /// grader did not write or another run holds it; with `replace`, emptied first.
  ResultsFolder(fs::path out, bool replace);
  ResultsFolder(const ResultsFolder&) = delete;
  ResultsFolder& operator=(const ResultsFolder&) = delete;
  ~ResultsFolder();

  const fs::path& path() const { return out_; }
  /// The submissions graded into it by earlier runs, by name.
  const std::map<std::string, Recorded>& recorded() const { return recorded_; }
  /// The earlier result of `name` when it graded exactly what `signature` says.
  std::optional<Recorded> unchanged(const std::string& name, const std::string& signature) const;

  /// Writes a submission's reports and marker (replacing its earlier folder whole, or not at all).
  /// Throws std::runtime_error when they cannot be written.
  void write(const SubmissionResult& result, const std::string& signature, const Kit& kit,
             double seconds);

  /// gradebook.csv and review.csv (when there is anything to review) of every submission in the
  /// folder; `note` adds a row to review.csv for the whole run. Throws std::runtime_error when
  /// they cannot be written.
  void write_gradebook(const std::string& note) const;

 private:
  fs::path out_;
  int lock_ = -1;
  std::map<std::string, Recorded> recorded_;
};

/// What a submission's grade depends on besides the kit: its task folders' files (names and
/// bytes). "" when a file cannot be read.
std::string submission_digest(const Submission& submission, const std::vector<int>& tasks);

}  // namespace springlab::grader
