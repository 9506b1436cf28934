// The kit as its build describes it to the grader (kit.toml, written by
// tests/grader/CMakeLists.txt): where the test programs, the parts of a submission library and
// the headers are, and how submission code is built.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace springlab::grader {

namespace fs = std::filesystem;

/// How submission code is compiled and linked for one of the two runs of every test.
struct Variant {
  std::string name;                  ///< "plain" or "sanitized"
  std::vector<std::string> compile;  ///< the compiler and its flags, before -c FILE -o OBJ
  std::vector<std::string> link;     ///< the compiler and its flags, before -o LIB OBJECTS
  std::vector<std::string> env;      ///< extra environment of the test processes
};

struct Kit {
  fs::path root;         ///< the kit's source folder
  fs::path starter;      ///< the starter code, tasks/ (stands in for missing files)
  fs::path solutions;    ///< the reference code, solutions/ (its times set the time limits); empty
                         ///< in a student release, which has none
  fs::path calibration;  ///< without solutions/: the reference's times, measured by the instructor
  fs::path pch;          ///< the folder of the precompiled headers submission code is built with
  fs::path headers;      ///< common/include: the only kit folder submission code may include from
  fs::path points;       ///< tests/points.toml
  fs::path nm;           ///< lists an object's symbols
  fs::path linker_script;  ///< defers a submission library's initialisers (deferred_init.ld)
  std::vector<fs::path> system_headers;  ///< the compiler's own include folders
  Variant plain, sanitized;
  /// Per task 1-5: its files, as "task1_two_masses/spring_damper.cpp".
  std::map<int, std::vector<std::string>> task_files;
  /// Per task: its program (the harness, and the plain worker) and its sanitized worker.
  std::map<int, fs::path> programs, sanitized_programs;
  /// Per task: what a submission library is linked from besides the submission's files.
  std::map<int, std::vector<fs::path>> library_parts;

  /// The folder of task n, e.g. "task1_two_masses".
  std::string task_folder(int n) const;
};

/// Reads a kit.toml. Throws std::runtime_error naming the file and the field when it is wrong.
Kit read_kit(const fs::path& file);

}  // namespace springlab::grader
