// Where submission code runs: every compiler, linker and test process of a submission in Linux
// namespaces of its own, made by bubblewrap (Debian's `bubblewrap`, Flatpak's sandbox). Inside,
// only the system's toolchain and libraries (/usr), the files the command needs (read-only but
// for its output folder) and a size-limited scratch exist; no network, no other process, no
// environment but the one given, an unprivileged user, and the whole sandbox dies with the
// grader. Where the kernel or a container refuses namespaces, the grader says so once and runs
// the same commands as an unprivileged user instead, one per command running at once where it
// can, the builds under a system-call filter that keeps them from reaching any other process
// (see tests/grader/README.md).
#pragma once

#include "process.hpp"

#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace springlab::grader {

namespace fs = std::filesystem;

/// A host path a sandboxed command sees.
struct Binding {
  fs::path path;          ///< on the host: a file or a folder
  fs::path inside;        ///< where the command sees it; empty: at the same path
  bool writable = false;  ///< only a command's own output folder is
};

/// What one command may see besides the system: given to Isolation::wrap.
struct View {
  std::vector<Binding> bindings;
  long scratch_mb = 64;  ///< the size of its writable /tmp, MB
  fs::path directory;    ///< its working folder, as the command sees it
  /// A test's harness and worker, not a build: the worker loads a stricter filter of its own
  /// (harness/sandbox.cpp) before any submission code runs, and the harness must signal it.
  bool test = false;
};

class Isolation {
 public:
  /// Finds out once whether namespaces can be had here (a sandbox that runs /bin/true), and
  /// whom to run as: the user nobody when the grader runs as root, else the grader's own user.
  /// `hide` lists folders no sandbox may show even where a system folder holds them (the kit,
  /// the work and results folders).
  static Isolation probe(std::vector<fs::path> hide);

  /// True when commands run in namespaces of their own.
  bool namespaces() const { return namespaces_; }
  /// Why they do not, in bubblewrap's or the system's words ("" when they do).
  const std::string& why_not() const { return why_not_; }
  /// The user id commands run as outside the sandbox: 65534 (nobody) when the grader is root,
  /// -1 for the grader's own user.
  uid_t run_as() const { return run_as_; }
  /// Where there are no namespaces and the grader is root: whether each command running at once
  /// has a user of its own (users_from() and up, ProcessPool::users_apart of them), so that none
  /// can signal, trace or read the processes of another; why not, when not.
  bool users_apart() const { return users_apart_; }
  const std::string& why_not_apart() const { return why_not_apart_; }
  static constexpr uid_t users_from = 65000;  // Debian's reserved 65000-65533: no one's
  /// The command line that runs `argv` (with environment `env`) confined to `view`; where there
  /// are no namespaces, `argv` itself, and the caller runs it as run_as() in view.directory.
  std::vector<std::string> wrap(const std::vector<std::string>& argv,
                                const std::vector<std::string>& env, const View& view) const;
  /// Confines `c` to `view`: its command line wrapped (its argv written with the paths the
  /// command sees), or, where there are no namespaces, run as run_as() (or a user apart) with
  /// the host's paths, and, unless it is a test, under build_filter().
  void confine(Command& c, const View& view) const;
  /// Whether the sandbox of a confined command that ended as `o` was never made, so that the
  /// command itself never ran (the grader's fault, not the code's). Decided from bubblewrap's
  /// status channel alone (Command::status_channel): once the command inside has ended, bubblewrap
  /// writes its exit code there, and it writes none when it failed before (making the namespaces,
  /// the mounts, starting the command). Never from the output, which the command writes.
  bool never_made(const Outcome& o) const;
  /// bubblewrap's own words for a sandbox never_made (its last line starting "bwrap: ").
  static std::string why_never_made(const Outcome& o);
  /// One paragraph for the run's output and review.csv: how submission code is confined here.
  std::string describe() const;
  /// Makes `folder` writable by the user commands run as (it must be the grader's own).
  void give_to_sandbox(const fs::path& folder) const;

  /// For tests: never use namespaces, as on a host that refuses them.
  static Isolation without_namespaces(const std::string& why);

  /// The system-call filter of a build (preprocessor, compiler, nm, linker) where there are no
  /// namespaces: anything a compiler does, but nothing that reaches another process (signals
  /// beyond its own process group, which it may not leave; tracing; another's memory, limits or
  /// scheduling) or the network. Refused calls fail with EPERM.
  static std::shared_ptr<const SystemCallFilter> build_filter();

 private:
  bool namespaces_ = false;
  std::string why_not_;
  uid_t run_as_ = uid_t(-1);
  bool users_apart_ = false;
  std::string why_not_apart_;
  std::shared_ptr<const SystemCallFilter> filter_;
  std::string bwrap_, setpriv_;
  std::vector<std::string> system_;  // bwrap's options for the system's folders
  std::vector<fs::path> hide_;
};

}  // namespace springlab::grader
