// A submission as the grader finds it: a copy of tasks/ (task1_two_masses/ ... task5_fabric/), a
// whole student repository (its tasks/), or a folder of the loose .cpp files, matched by name. The
// grader only reads it: every file it compiles is a private copy, so the submission on disk is
// never written, and nothing outside the copy can be reached by a relative #include.
#pragma once

#include "kit.hpp"
#include "usage_error.hpp"

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace springlab::grader {

enum class Layout { tasks_folder, repository, loose_files };

/// Where one task's files of a submission are.
struct TaskSource {
  fs::path folder;                   ///< searched for the task's files ("" if the task has none)
  std::vector<std::string> found;    ///< the kit's file names found there, e.g. "spring_damper.cpp"
  std::vector<std::string> missing;  ///< the kit's file names not found: the starter code is used
  std::vector<std::string> notes;    ///< why its folder was left out, if it was
};

struct Submission {
  std::string name;  ///< the base name of its folder: its row in the gradebook
  fs::path folder;   ///< absolute
  Layout layout = Layout::tasks_folder;
  std::map<int, TaskSource> tasks;  ///< 1-5
  std::vector<std::string> notes;   ///< what was left out or looked for elsewhere, and why
  /// Why the grader could not read it at all (a folder it may not read): not graded, never a 0.
  std::string fault;
  /// True when not one of the kit's files was found (a wrong folder, or an empty submission).
  bool empty() const;
};

/// Finds the task files of the submission in `folder`, or in its one subfolder when it holds
/// nothing else (a download that wraps the repository in a folder of its own). Linked folders
/// are never followed (git and zip keep links; one could reach the kit's solutions or a
/// classmate's copy). Throws UsageError when `folder` is not a folder.
Submission find_submission(const fs::path& folder, const Kit& kit);

/// The most bytes a task's file, or any other file beside it, may have.
constexpr std::uintmax_t largest_file = 1 << 20;

/// What the copy of one task holds, beside the files themselves: what a student should know.
struct TaskCopy {
  fs::path folder;                 ///< destination/tasks/<task folder>
  std::vector<std::string> notes;  ///< files left out or replaced, and why
  std::string problem;             ///< why the task cannot be graded ("" when it can)
  std::string digest;  ///< every file's name, size and hash: equal for copies that hold the same
                       ///< files (same_files() tells for sure), so equal copies are graded once
};

/// Copies task `task` of `submission` into `destination`/tasks/<task folder>/: the task's files,
/// the starter code in place of missing ones, and the submission's other regular files of that
/// folder (its own headers) up to a size limit; never links. A task file larger than
/// largest_file is not copied (the copy's `problem` says so): no file is ever read whole.
TaskCopy copy_task(const Submission& submission, int task, const Kit& kit,
                   const fs::path& destination);

/// A file's size and a 64-bit hash of its bytes, read in pieces.
std::string file_digest(const fs::path& file);

/// True when the two files hold the same bytes.
bool same_file(const fs::path& a, const fs::path& b);

/// True when the two folders hold the same file names with the same bytes.
bool same_files(const fs::path& a, const fs::path& b);

/// "a copy of tasks/", "a student repository", "loose files".
std::string to_string(Layout layout);

}  // namespace springlab::grader
