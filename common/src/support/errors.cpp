#include "springlab/errors.hpp"

#include <sstream>
#include <string>

namespace springlab {
namespace {

std::string where_to_edit(const std::string& file) {
  // __FILE__ may be absolute; the student knows the file by its path inside the kit.
  const auto at = file.rfind("tasks/");
  return at == std::string::npos ? file : file.substr(at);
}

std::string divergence_message(double time, int particle, const std::string& quantity,
                               const std::string& why) {
  std::ostringstream out;
  out << "the simulation diverged at t = " << time << " s: ";
  if (particle >= 0) out << "particle " << particle << ", ";
  out << quantity << ": " << why;
  return out.str();
}

}  // namespace

InvalidParameter::InvalidParameter(std::string field, std::string value, std::string allowed)
    : std::invalid_argument(field + " = " + value + ": " + allowed),
      field_(std::move(field)),
      value_(std::move(value)),
      allowed_(std::move(allowed)) {}

DivergenceError::DivergenceError(double time, int particle, std::string quantity, std::string why)
    : std::runtime_error(divergence_message(time, particle, quantity, why)),
      time_(time),
      particle_(particle),
      quantity_(std::move(quantity)) {}

NotImplemented::NotImplemented(int task, std::string function, std::string file)
    : std::logic_error("Task " + std::to_string(task) + " is not implemented yet: write " +
                       function + " in " + where_to_edit(file) + " (see handout section " +
                       std::to_string(task) + ")"),
      task_(task) {}

NotImplemented::NotImplemented(std::string message, int task)
    : std::logic_error(std::move(message)), task_(task) {}

}  // namespace springlab
