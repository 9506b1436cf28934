// What a submission's code may reach, checked on what the compiler read and what the objects
// name: its own files, the kit's headers (common/include) and the compiler's own headers; never
// the solutions, the tests, Catch2, a main() of its own, or the kit's reference code.
#pragma once

#include "kit.hpp"

#include <string>
#include <vector>

namespace springlab::grader {

/// The files a compilation read, from the dependency file the compiler wrote (-MD -MF).
std::vector<fs::path> read_dependencies(const fs::path& dependency_file);

/// Why a submission file may not include `file`, or "" when it may. `copy` is the folder of the
/// task's private copy; `pch` the folder of the precompiled header.
std::string include_problem(const fs::path& file, const fs::path& copy, const fs::path& pch,
                            const Kit& kit);

/// What is wrong with the symbols of a submission's objects, given `nm -P -A` output: each
/// problem once, in words for the student. Empty when nothing is.
std::vector<std::string> symbol_problems(const std::string& nm_output);

/// What else the objects call that no task needs (ending the program, files, programs, threads,
/// signals, raw system calls, sleeping, the environment), once each: for the instructor to
/// review, not a verdict (the test process is kept from doing most of it anyway).
std::vector<std::string> review_notes(const std::string& nm_output);

}  // namespace springlab::grader
