// What a submission's source may hold, checked before it is compiled: C++ and nothing that
// reaches past it. No inline assembler (the assembler reads any file it is pointed at and puts
// any bytes among code), no compiler attributes or pragmas (they place data among code or switch
// the sanitizers off), no #include of anything but the standard library, Eigen, the kit's public
// headers and the task's own files, and no macro that tells the plain build from the sanitized
// one (both builds define the same macros, so that both compute the same thing). Checked twice:
// on the files as written, and on what the preprocessor made of them (a macro can build a
// keyword out of pieces), each breach named by file and line.
#pragma once

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
/// a keyword, attribute or pragma that a macro brought into the copy's lines, or a header that
/// the copy's files included and may not.
Preprocessed check_preprocessed(std::istream& output, const IncludeRoots& roots);

}  // namespace springlab::grader
