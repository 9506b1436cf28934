// The type of an exception, named as a student reads it in the handout and the headers
// ("StepFailed", "std::out_of_range"), for the feedback: the type a test expected beside the one
// it got, and what a probe's call threw. Only springlab's and the standard library's types are
// named; any other is "an exception of another type".
#pragma once

#include "springlab/errors.hpp"

#include <exception>
#include <functional>
#include <new>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>

namespace springlab::testing {

/// An exception that student code threw in the grader's worker, relayed to the test by the
/// harness under its own type's name where the harness cannot throw that type itself (a plain
/// std::exception, a class of the student's own).
class RelayedException : public std::exception {
 public:
  RelayedException(std::string type, std::string message)
      : type_(std::move(type)), message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }
  const std::string& type() const { return type_; }

 private:
  std::string type_, message_;
};

template <class Kind>
bool is_a(const std::exception& error) {
  return dynamic_cast<const Kind*>(&error) != nullptr;
}

/// The name of the type of `error`, the most derived one of those the kit knows.
inline std::string exception_type(const std::exception& error) {
  if (const auto* relayed = dynamic_cast<const RelayedException*>(&error))
    return relayed->type().empty() ? "an exception of another type (derived from std::exception)"
                                   : relayed->type();
  if (is_a<StepFailed>(error)) return "StepFailed";
  if (is_a<DivergenceError>(error)) return "DivergenceError";
  if (is_a<InvalidParameter>(error)) return "InvalidParameter";
  if (is_a<NotImplemented>(error)) return "NotImplemented";
  if (is_a<std::out_of_range>(error)) return "std::out_of_range";
  if (is_a<std::invalid_argument>(error)) return "std::invalid_argument";
  if (is_a<std::domain_error>(error)) return "std::domain_error";
  if (is_a<std::length_error>(error)) return "std::length_error";
  if (is_a<std::logic_error>(error)) return "std::logic_error";
  if (is_a<std::range_error>(error)) return "std::range_error";
  if (is_a<std::overflow_error>(error)) return "std::overflow_error";
  if (is_a<std::underflow_error>(error)) return "std::underflow_error";
  if (is_a<std::runtime_error>(error)) return "std::runtime_error";
  if (is_a<std::bad_alloc>(error)) return "std::bad_alloc";
  if (is_a<std::bad_function_call>(error)) return "std::bad_function_call";
  if (is_a<std::bad_cast>(error)) return "std::bad_cast";
  if (typeid(error) == typeid(std::exception)) return "std::exception";
  return "an exception of another type (derived from std::exception)";
}

/// "StepFailed (\"what\")" for the exception being handled (call inside a catch block).
inline std::string current_exception_text() {
  try {
    throw;
  } catch (const std::exception& error) {
    return exception_type(error) + " (\"" + error.what() + "\")";
  } catch (...) {
    return "an exception of a type that is not std::exception's";
  }
}

}  // namespace springlab::testing
