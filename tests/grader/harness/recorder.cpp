#include "recorder.hpp"

#include "springlab/errors.hpp"

#include <cxxabi.h>

#include <cstdlib>
#include <memory>
#include <typeinfo>

namespace springlab::grading {
namespace {

const Implementation* submission = nullptr;
TranscriptWriter* out = nullptr;
std::exception_ptr model_exception;  // what the model last threw into the submission's code

// The type of the exception being handled, as C++ spells it ("std::length_error").
std::string current_type_name() {
  const std::type_info* type = abi::__cxa_current_exception_type();
  if (type == nullptr) return "";
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> name(
      abi::__cxa_demangle(type->name(), nullptr, nullptr, &status), &std::free);
  return status == 0 && name ? name.get() : type->name();
}

// Writes down how the exception being handled left the submission's function. A standard
// exception's message is its type's name, a line break, then what(): the harness throws the
// same type again where it can, and names it where it cannot (replayer.cpp).
void write_thrown() {
  const std::exception_ptr thrown = std::current_exception();
  out->event(Event::thrown);
  std::uint8_t kind = std::uint8_t(Thrown::other);
  int task = 0;
  std::string message;
  try {
    std::rethrow_exception(thrown);
  } catch (const NotImplemented& e) {
    kind = std::uint8_t(Thrown::not_implemented), task = e.task(), message = e.what();
  } catch (const StepFailed& e) {
    kind = std::uint8_t(Thrown::step_failed), message = e.what();
  } catch (const std::exception& e) {
    kind = std::uint8_t(Thrown::standard), message = current_type_name() + "\n" + e.what();
  } catch (...) {
  }
  if (thrown == model_exception) kind = std::uint8_t(Thrown::model);
  out->out().put_all(kind, task, message.substr(0, 4096));
  out->flush();
}

// call(): runs the submission's function; the outputs are written after it returns.
template <class Call, class... Outputs>
auto record(Function f, std::uint64_t inputs, Call call, const Outputs&... outputs) {
  out->event(Event::call);
  out->out().put_all(std::uint8_t(f), std::int64_t(inputs));
  // Written before the submission's code runs: should it crash or never return, the harness has
  // every earlier answer, so it names this function, not the one before it.
  out->flush(true);
  try {
    if constexpr (std::is_void_v<decltype(call())>) {
      call();
      out->event(Event::result);
      out->out().put_all(outputs...);
      out->flush();
    } else {
      auto result = call();
      out->event(Event::result);
      out->out().put_all(result, outputs...);
      out->flush();
      return result;
    }
  } catch (...) {
    write_thrown();
    throw;
  }
}

// The model as the submission's integrator sees it: each evaluation written down.
AccelerationFunction watched(const AccelerationFunction& model) {
  return [&model](const Vectors& r, const Vectors& v) -> const Vectors& {
    out->event(Event::callback);
    out->out().put_all(r, v);
    try {
      const Vectors& a = model(r, v);
      out->event(Event::callback_return);
      out->out().put(std::int64_t(hash_of(a)));
      out->flush();
      return a;
    } catch (...) {
      model_exception = std::current_exception();
      out->event(Event::callback_throw);
      out->flush();
      throw;
    }
  };
}

Vec2 spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  return record(Function::spring_force, hash_of(r_p, r_q, k, rest_length),
                [&] { return submission->spring_force(r_p, r_q, k, rest_length); });
}

Vec2 damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return record(Function::damper_force, hash_of(v_p, v_q, b),
                [&] { return submission->damper_force(v_p, v_q, b); });
}

void explicit_euler_step(const AccelerationFunction& a, double h, Vectors& r, Vectors& v) {
  const AccelerationFunction model = watched(a);
  record(
      Function::explicit_euler_step, hash_of(h, r, v),
      [&] { submission->explicit_euler_step(model, h, r, v); }, r, v);
}

std::vector<Spring> structural_springs(int rows, int cols, const SpringFamilyParameters& p) {
  return record(Function::structural_springs, hash_of(rows, cols, p),
                [&] { return submission->structural_springs(rows, cols, p); });
}

void accumulate_spring_forces(const std::vector<Spring>& springs, const Vectors& r,
                              const Vectors& v, Vectors& force) {
  record(
      Function::accumulate_spring_forces, hash_of(springs, r, v, force),
      [&] { submission->accumulate_spring_forces(springs, r, v, force); }, force);
}

std::vector<Spring> shear_springs(int rows, int cols, const SpringFamilyParameters& p) {
  return record(Function::shear_springs, hash_of(rows, cols, p),
                [&] { return submission->shear_springs(rows, cols, p); });
}

void verlet_step(const AccelerationFunction& a, double h, Vectors& r, Vectors& v,
                 VerletHistory& history) {
  const AccelerationFunction model = watched(a);
  record(
      Function::verlet_step, hash_of(h, r, v, history),
      [&] { submission->verlet_step(model, h, r, v, history); }, r, v, history);
}

std::vector<Spring> bend_springs(int rows, int cols, const SpringFamilyParameters& p) {
  return record(Function::bend_springs, hash_of(rows, cols, p),
                [&] { return submission->bend_springs(rows, cols, p); });
}

void add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  record(
      Function::add_gravity, hash_of(mass, g, force),
      [&] { submission->add_gravity(mass, g, force); }, force);
}

void add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v, Vectors& force) {
  // The wind is the same object in both runs of the test; its time and the state are hashed.
  record(
      Function::add_wind, hash_of(t, r, v, force),
      [&] { submission->add_wind(wind, t, r, v, force); }, force);
}

void hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  record(
      Function::hold_pinned, hash_of(pinned, acceleration),
      [&] { submission->hold_pinned(pinned, acceleration); }, acceleration);
}

}  // namespace

Implementation recording(const Implementation& functions, TranscriptWriter& writer) {
  submission = &functions;
  out = &writer;
  return {"submission",
          functions.student_task,
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
          hold_pinned};
}

}  // namespace springlab::grading
