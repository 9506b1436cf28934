// What a submission's source may hold, checked before it is compiled: C++ and nothing that
// reaches past it. No inline assembler (the assembler reads any file it is pointed at and puts
// any bytes among code), no compiler attributes or pragmas (they place data among code or switch
// the sanitizers off), no #include of anything but the standard library, Eigen, the kit's public
// headers and the task's own files, and no macro that tells the plain build from the sanitized
// one (both builds define the same macros, so that both compute the same thing); no line markers
// and no bytes on which a reading of the text and the compiler's could differ. Checked three
// times (README.md, "The source policy"): on the files as written, on the compiler's own reading
// of them against empty stand-ins for the headers (all of which is the submission's), and on
// what the build's preprocessing made of them (a macro can build a keyword out of pieces), each
// breach named by file and line.
#pragma once

#include "kit.hpp"

#include <filesystem>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace springlab::grader {

namespace fs = std::filesystem;

struct PolicyBreach {
  std::string file;  ///< the file's name in the task's folder
  int line = 0;      ///< 1-based
  std::string what;  ///< what is not allowed there, and why, in a student's words
  /// "shear_springs.cpp:12: ..."
  std::string text() const;
};

/// True for the C++ standard library's headers (and the C headers it includes, <math.h>, ...),
/// by the name an #include gives them.
bool is_standard_header(std::string_view name);

/// True when `file` lies in `folder` (both lexically normal, as canonical paths are): compared
/// by path element, so that /a/bc is not within /a/b.
bool is_within(const fs::path& file, const fs::path& folder);

/// The first breach in `files` (their names in `copy`, read from there), if any.
std::optional<PolicyBreach> check_sources(const fs::path& copy,
                                          const std::vector<std::string>& files);

/// Where headers come from, for check_preprocessed.
struct IncludeRoots {
  fs::path copy;                   ///< the task's private copy
  fs::path kit_headers;            ///< common/include
  std::vector<fs::path> standard;  ///< the compiler's own include folders
  std::vector<fs::path> eigen;     ///< Eigen's include folders
};

/// What the preprocessor's output of one file shows.
struct Preprocessed {
  std::optional<PolicyBreach> breach;  ///< the first breach, if any
  std::vector<std::string> own_files;  ///< the copy's files it read, by name
};

/// Checks the preprocessor's output for one file (`-E`, with line markers), one line at a time:
/// a keyword, attribute or pragma that a macro brought into the copy's lines, a header that the
/// copy's files included and may not, or a line marker that the preprocessor did not make (one
/// written in the source: it would pass the lines after it off as a system header's).
Preprocessed check_preprocessed(std::istream& output, const IncludeRoots& roots);

/// The policy's own reading of a task's files, in which the compiler does the tokenising: each
/// file preprocessed against a folder of empty stand-ins for every header a submission may
/// include (the standard library's by name, Eigen's and the kit's by the names they have on
/// disk), with the macros the precompiled header defines (so that #if and the library's macros
/// go as in the build). Every line of that output is the submission's own, as the compiler read
/// it, whatever its files say about themselves (line markers, odd bytes, where a directive
/// starts): all of it is checked.
struct StandIns {
  fs::path folder;  ///< the empty headers, by the name an #include gives them
  fs::path macros;  ///< what the precompiled header defines beyond the compiler itself
};

/// The plain build's compiler and flags (`compile`) for the policy's own reading: without its
/// include folders and precompiled header, with only the stand-ins to include (-nostdinc).
/// Add `-include macros -E FILE -o OUTPUT` to preprocess; `-dM -E` to list the macros.
std::vector<std::string> stand_in_flags(const std::vector<std::string>& compile,
                                        const StandIns& stand_ins);

/// The lines of `with` (a `-dM` listing) that `without` lacks: the macros the precompiled header
/// adds (the compiler's own would be defined twice, and some of them may not).
std::string added_definitions(const std::string& with, const std::string& without);

/// Writes the stand-ins for the kit headers and Eigen folders of `roots`, and the macros file.
void write_stand_ins(const StandIns& stand_ins, const IncludeRoots& roots,
                     const std::string& macros);

/// Writes the stand-ins for `kit`'s plain build into `folder` (emptied first), listing the
/// precompiled header's macros with the build's compiler (outside the sandbox: it reads none of
/// a submission's files). Throws std::runtime_error when the compiler fails: the kit is broken.
StandIns prepare_stand_ins(const Kit& kit, const fs::path& folder);

/// Checks the output of the policy's own reading of one of the copy's files: every line (all of
/// it is the copy's), and every line marker, which must be one the preprocessor made itself.
Preprocessed check_stand_in_output(std::istream& output, const fs::path& copy,
                                   const StandIns& stand_ins);

}  // namespace springlab::grader
