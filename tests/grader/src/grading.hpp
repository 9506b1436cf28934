// Grading many submissions at once: each task of each submission is copied, compiled (its own
// files only: the kit and the reference objects are built once), checked and linked into a
// library; then every test of the task runs as a process of its own under limits, first plain
// and, when it passes, again with the sanitizers. Task copies with the same files are graded once.
#pragma once

#include "isolation.hpp"
#include "kit.hpp"
#include "points.hpp"
#include "process.hpp"
#include "submission.hpp"
#include "task_results.hpp"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace springlab::grader {

struct Settings {
  fs::path work;                        ///< private copies, objects and libraries (emptied first)
  int jobs = 2;                         ///< processes at once
  double time_factor = 10.0;            ///< a test may take this many times the reference's time...
  double time_floor = 2.0;              ///< ...but never less than this, s
  long memory_mb = 1024;                ///< MB of memory per test process
  std::size_t output_kept = 64 * 1024;  ///< bytes of a test's output kept
  std::size_t output_limit = 8u << 20;  ///< bytes: printing more stops the test
  std::vector<int> tasks{1, 2, 3, 4, 5};  ///< the tasks graded
  bool hidden = true;      ///< whether the hidden tests run too (a student's check: false)
  bool raw = false;        ///< keep Catch2's own form of a failure (file, line, expression)
  bool keep_work = false;  ///< keep the copies, objects and libraries (else removed as they end)
  /// Run each task's tests in order, plainly, and stop at its first failure (the rest are "not
  /// run"): what a student reads first, at a fraction of the cost (springlab-mutate's measure).
  bool first_failure = false;
};

struct SubmissionResult {
  Submission submission;
  std::map<int, TaskResult> tasks;
  double points() const;
  double max_points() const;
  /// The first of its tasks' faults ("task 2: ..."), "" when every task was graded.
  std::string fault() const;
};

/// A test's wall time with the reference code, and its task.
struct ReferenceTime {
  int task = 0;
  double seconds = 0.0;  ///< s
};
/// Each test's time by name, per variant ("plain", "sanitized").
using Calibration = std::map<std::string, std::map<std::string, ReferenceTime>>;

/// The processes of one kind a run started (preprocess, compile, nm, link, test, each plain or
/// sanitized): how many, and their wall time summed. Where a batch's time goes.
struct PhaseTime {
  long count = 0;
  double wall_seconds = 0.0;
};
using PhaseTimes = std::map<std::string, PhaseTime>;

class Grader {
 public:
  /// Every command on submission code runs confined by `isolation` (isolation.hpp).
  Grader(const Kit& kit, const std::vector<TestInfo>& tests, Settings settings,
         const Isolation& isolation);

  /// Grades the kit's own solutions with generous limits and keeps each test's time, for the
  /// tasks being graded whose times `cache` lacks or whose programs changed since. Throws
  /// std::runtime_error when a reference test fails: the kit is broken, and no submission could be
  /// graded fairly. `progress` is told of each task measured, in words. Returns false when the
  /// times were measured but `cache` could not be written (said to `progress`; the next run
  /// measures them again).
  bool calibrate(const fs::path& cache,
                 const std::function<void(const std::string&)>& progress = {});

  /// Grades every submission. `task_done` is called as each task of a submission is finished
  /// (in any order), `submission_done` once all of a submission's tasks are.
  std::vector<SubmissionResult> grade(
      const std::vector<Submission>& submissions,
      const std::function<void(const SubmissionResult&, int task)>& task_done,
      const std::function<void(const SubmissionResult&)>& submission_done);

  /// How the time limit is set, in words.
  std::string time_limit_text() const;

  /// The processes grade() started so far, by kind (not calibrate()'s).
  const PhaseTimes& phase_times() const { return phase_times_; }

 private:
  struct TaskBuild;
  class Pipeline;
  class Batch;
  const Kit& kit_;
  const std::vector<TestInfo>& tests_;
  Settings settings_;
  const Isolation& isolation_;
  Calibration calibration_;
  mutable PhaseTimes phase_times_;  // counted by the pipeline as each process ends

  Limits test_limits(const TestInfo& test, const Variant& variant) const;
  std::vector<SubmissionResult> run(
      const std::vector<Submission>& submissions, bool generous,
      const std::function<void(const SubmissionResult&, int)>& task_done,
      const std::function<void(const SubmissionResult&)>& done);
  /// Grades the kit's solutions in `tasks`, every test plainly and sanitized, with generous
  /// limits: their times (calibrate).
  std::vector<SubmissionResult> measure_reference(
      const std::vector<int>& tasks, const std::function<void(const std::string&)>& progress);
};

}  // namespace springlab::grader
