// The errors springlab reports. Each one says what went wrong in words a student can act on.
#pragma once

#include <stdexcept>
#include <string>

namespace springlab {

/// A parameter outside its allowed range: names the field, the value and the range.
class InvalidParameter : public std::invalid_argument {
 public:
  InvalidParameter(std::string field, std::string value, std::string allowed);
  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }
  const std::string& allowed() const { return allowed_; }

 private:
  std::string field_, value_, allowed_;
};

/// A step that could not be completed (for example an iteration inside the step did not settle).
/// Student code may throw it; the simulation reports it as a divergence at the current time.
class StepFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The simulation left the range of physically meaningful values: says when, where and why.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(double time, int particle, std::string quantity, std::string why);
  double time() const { return time_; }                      ///< s
  int particle() const { return particle_; }                 ///< index, or -1 for the whole scene
  const std::string& quantity() const { return quantity_; }  ///< e.g. "velocity.x", "total energy"

 private:
  double time_;
  int particle_;
  std::string quantity_;
};

/// Thrown by a task function that the student has not written yet (see todo.hpp).
class NotImplemented : public std::logic_error {
 public:
  NotImplemented(int task, std::string function, std::string file);
  /// The same error with its message already written (the grader relays it between processes).
  NotImplemented(std::string message, int task);
  int task() const { return task_; }

 private:
  int task_;
};

}  // namespace springlab
