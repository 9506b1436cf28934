// The transcript: what the submission's code did, streamed one way from the worker (the process
// that runs it) to the harness (the process that decides). For each call of one of the graded
// task's functions: the function, a hash of its inputs, each call it made back into the model
// (with its inputs, and a hash of the model's answer), and its outputs or the exception it threw.
// The harness runs the same test without the submission's code, takes each answer from here and
// checks every input hash: so an answer counts only for the very inputs the test gave.
#pragma once

#include "springlab/parameters.hpp"
#include "springlab/types.hpp"

#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace springlab::grading {

/// The task functions, in the Implementation table's order.
enum class Function : std::uint8_t {
  spring_force,
  damper_force,
  explicit_euler_step,
  structural_springs,
  accumulate_spring_forces,
  shear_springs,
  verlet_step,
  bend_springs,
  add_gravity,
  add_wind,
  hold_pinned
};

enum class Event : std::uint8_t {
  loaded = 1,       ///< the worker has the library loaded and runs the test
  call,             ///< function, input hash
  callback,         ///< the function called the model: r, v
  callback_return,  ///< the model answered: hash of the acceleration
  callback_throw,   ///< the model threw
  result,           ///< the function returned: its outputs
  thrown,           ///< the function threw: kind, task, message
  end,              ///< the test is over
  forbidden,        ///< the worker was stopped at a forbidden system call: its number
  refused,          ///< the worker found code it may not run: why
};

/// How an exception crossed from the worker to the harness.
enum class Thrown : std::uint8_t { not_implemented, step_failed, model, standard, other };

/// Bytes in the transcript's encoding; also what input hashes are taken over.
class Encoder {
 public:
  void put(std::uint8_t x) { bytes_.push_back(static_cast<char>(x)); }
  void put(std::int64_t x) { raw(&x, sizeof x); }
  void put(double x) { raw(&x, sizeof x); }
  void put(int x) { put(std::int64_t(x)); }
  void put(bool x) { put(std::uint8_t(x)); }
  void put(const std::string& x);
  void put(const Vec2& x) { raw(x.data(), sizeof(double) * 2); }
  void put(const Vectors& x);
  void put(const Eigen::VectorXd& x);
  void put(const std::vector<bool>& x);
  void put(const Spring& x);
  void put(const std::vector<Spring>& x);
  void put(const SpringFamilyParameters& x);
  void put(const VerletHistory& x);
  template <class... T>
  void put_all(const T&... x) {
    (put(x), ...);
  }
  std::string& bytes() { return bytes_; }

 private:
  void raw(const void* data, std::size_t size);
  std::string bytes_;
};

/// The hash of some values, as the transcript compares inputs.
template <class... T>
std::uint64_t hash_of(const T&... x) {
  Encoder e;
  e.put_all(x...);
  return std::hash<std::string>{}(e.bytes());
}

/// The worker's side: events buffered and written to a file descriptor.
class TranscriptWriter {
 public:
  explicit TranscriptWriter(int fd) : fd_(fd) {}
  Encoder& out() { return encoder_; }
  void event(Event e) { encoder_.put(std::uint8_t(e)); }
  /// Writes what is buffered when enough has gathered, or always with `now`.
  void flush(bool now = false);
  /// For a signal handler: the buffered bytes, then the event "forbidden" and `number`.
  void forbidden(long number);

 private:
  int fd_;
  Encoder encoder_;
};

/// The harness's side gave up: the worker stopped, or its answers do not fit the test.
class ReplayStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The harness's side: reads events from a file descriptor, blocking; checks sizes against what
/// the test expects, so that no transcript can make the harness allocate without bound.
class TranscriptReader {
 public:
  /// `watch` is called every 20 ms or so while the transcript is read (the harness checks the
  /// worker's memory with it).
  TranscriptReader(int fd, std::function<void()> watch) : fd_(fd), watch_(std::move(watch)) {}
  Event event();
  std::uint8_t byte();
  std::int64_t integer();
  double number();
  std::string text(std::size_t longest);
  void get(Vec2& x);
  void get(Vectors& x, Eigen::Index columns);  ///< columns: what the test holds, or -1: any
  void get(std::vector<Spring>& x);
  void get(VerletHistory& x, Eigen::Index columns);
  bool at_end() const { return ended_; }  ///< the worker closed the transcript

 private:
  void read(void* data, std::size_t size);
  int fd_;
  std::function<void()> watch_;
  std::chrono::steady_clock::time_point last_watch_{};
  std::string buffer_;
  std::size_t at_ = 0;
  bool ended_ = false;
};

}  // namespace springlab::grading
