// Running other programs under limits: the compiler and linker on a submission's files, and the
// test harness with a submission's code in it. Nothing a child prints, writes or returns is taken
// on trust: the grader measures time and memory itself, keeps a bounded part of the output and
// stops the whole process group when a limit is hit.
#pragma once

#include <linux/filter.h>
#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace springlab::grader {

struct Limits {
  double wall_seconds = 60.0;            ///< s of real time, then the group is killed
  double cpu_seconds = 60.0;             ///< s of processor time (RLIMIT_CPU, whole seconds)
  long address_space_mb = 4096;          ///< MB (RLIMIT_AS); 0: none (sanitizers need terabytes)
  long resident_mb = 0;                  ///< MB of resident memory, watched; 0: not watched
  long file_size_mb = 0;                 ///< MB: the largest file the child may write
  std::size_t output_kept = 64 * 1024;   ///< bytes of stdout and stderr kept, the rest counted
  std::size_t output_limit = 8u << 20;   ///< bytes: printing more stops the child
  std::size_t records_limit = 1u << 20;  ///< bytes accepted on the record channel (fd 3)
};

/// A system-call filter (seccomp's classic BPF program) that a child loads just before it starts
/// its program, and that everything the program starts inherits. Its rules may compare a pid
/// with `own_group`, which the child replaces with its own pid, known only once it is forked: as
/// the leader of a process group of its own (setsid), that is its group's id too.
struct SystemCallFilter {
  static constexpr std::uint32_t own_group = 0x5eed0001;  // above any pid (at most 2^22)
  std::vector<sock_filter> program;
};

struct Command {
  std::vector<std::string> argv;  ///< argv[0] is the program's path
  std::vector<std::string> env;   ///< the whole environment, "NAME=value"
  std::string directory;          ///< working directory
  std::string secret;             ///< when set: sent on fd 4; records are read from fd 3
  /// When set: a pipe on fd 5 for the sandbox's own report (bubblewrap's --json-status-fd), read
  /// into Outcome::status. The sandbox closes it before it starts the command inside, so nothing
  /// the command runs can write there.
  bool status_channel = false;
  Limits limits;
  uid_t run_as = uid_t(-1);  ///< when set (the grader is root): the user it runs as
  gid_t group = gid_t(-1);   ///< ...and its group; unset: the group with run_as's number
  /// With run_as: the first of a range of users, one per process slot of the pool, so that no
  /// two commands running at once share a user (ProcessPool::users_apart).
  bool user_per_slot = false;
  std::shared_ptr<const SystemCallFilter> filter;  ///< when set: loaded before the program starts
};

/// Why the grader stopped a child, if it did.
enum class Stop { none, wall_time, cpu_time, memory, output };

struct Outcome {
  bool exited = false;  ///< ended by exit(); then exit_code is its status
  int exit_code = 0;
  int signal = 0;  ///< the signal that ended it, when !exited
  Stop stopped = Stop::none;
  double wall_seconds = 0;  ///< from start to end, s
  double cpu_seconds = 0;   ///< user + system, s
  long peak_resident_kb = 0;
  std::string output;            ///< the first output_kept bytes of stdout and stderr, interleaved
  std::size_t output_bytes = 0;  ///< everything printed, bytes
  std::string records;           ///< what arrived on fd 3 (at most records_limit bytes)
  std::string status;            ///< what arrived on fd 5 (Command::status_channel; 64 kB at most)
  std::string start_error;       ///< set when the program could not be started at all
};

/// Thrown by ProcessPool::run when the grader was asked to stop (interrupt()): every command it
/// had started has been killed, with everything each one started.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal) : std::runtime_error("interrupted"), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// Asks every ProcessPool to stop at once; safe in a signal handler (SIGINT, SIGTERM, SIGHUP).
void interrupt(int signal);

/// Runs commands, at most `parallel` at once, in one thread. `done` is called with each
/// command's outcome as it ends and may add further commands.
class ProcessPool {
 public:
  explicit ProcessPool(int parallel);
  ~ProcessPool();
  ProcessPool(const ProcessPool&) = delete;
  ProcessPool& operator=(const ProcessPool&) = delete;

  void add(Command command, std::function<void(Outcome)> done);

  /// How many users apart a command with user_per_slot may take: its run_as plus a slot number
  /// below this (at most `parallel` are in use at once).
  static constexpr int users_apart = 534;

  /// Returns once every command added, including those added by callbacks, has ended. Throws
  /// Interrupted after interrupt(), its commands killed.
  void run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The environment a child gets: a fixed PATH and locale, nothing of the grader's own.
std::vector<std::string> plain_environment();

}  // namespace springlab::grader
