#include "replayer.hpp"

#include "exception_names.hpp"
#include "springlab/errors.hpp"

#include <chrono>
#include <new>
#include <stdexcept>
#include <typeinfo>

namespace springlab::grading {
namespace {

TranscriptReader* in = nullptr;
std::optional<std::string> failure;
long calls = 0;                      // replayed so far, to say which one failed
const char* open_call = nullptr;     // the function whose answer is awaited
const char* open_at_stop = nullptr;  // the one that was awaited when the replay stopped
std::string open_inputs;             // the awaited call's inputs in words ("rows = 1, cols = 2")
std::string inputs_at_stop;          // those of the call awaited when the replay stopped
std::chrono::steady_clock::time_point waiting_since;

// Something for Catch2 to report as an unknown exception, as the worker's was.
struct ForeignException {};

const char* name_of(Function f) {
  static const char* names[] = {"spring_force",
                                "damper_force",
                                "explicit_euler_step",
                                "structural_springs",
                                "accumulate_spring_forces",
                                "shear_springs",
                                "verlet_step",
                                "bend_springs",
                                "add_gravity",
                                "add_wind",
                                "hold_pinned"};
  return names[std::size_t(f)];
}

[[noreturn]] void stop(const std::string& why) {
  if (open_at_stop == nullptr) open_at_stop = open_call, inputs_at_stop = open_inputs;
  give_up(why);
  throw ReplayStopped(why);
}

// The next event, which must be `want`; the worker's own stops end the replay with their reason.
Event next(std::initializer_list<Event> want) {
  Event e{};
  try {
    e = in->event();
  } catch (const ReplayStopped& stopped) {
    stop(stopped.what());
  }
  if (e == Event::forbidden) stop("forbidden " + std::to_string(in->integer()));
  if (e == Event::refused) stop("refused " + in->text(4096));
  for (const Event w : want)
    if (e == w) return e;
  stop("the code's answers do not fit this test (event " + std::to_string(int(e)) + ")");
}

// The standard exception `type` (as C++ spells it) with `message`, thrown again as that type
// where it is one of the standard library's with a message, so that the test sees the type the
// submission threw; any other type is relayed under its name (exception_names.hpp).
[[noreturn]] void throw_standard(const std::string& type, const std::string& message) {
  if (type == "std::out_of_range") throw std::out_of_range(message);
  if (type == "std::length_error") throw std::length_error(message);
  if (type == "std::invalid_argument") throw std::invalid_argument(message);
  if (type == "std::domain_error") throw std::domain_error(message);
  if (type == "std::logic_error") throw std::logic_error(message);
  if (type == "std::range_error") throw std::range_error(message);
  if (type == "std::overflow_error") throw std::overflow_error(message);
  if (type == "std::underflow_error") throw std::underflow_error(message);
  if (type == "std::runtime_error") throw std::runtime_error(message);
  if (type == "std::bad_alloc")
    throw testing::RelayedException(
        type, message + " (out of memory, or a size below zero turned into a huge one?)");
  // Any other type (a plain std::exception, a class of the student's own) keeps its name.
  throw testing::RelayedException(type, message);
}

// libstdc++'s words for .at() past the end ("vector::_M_range_check: __n (which is 9) >=
// this->size() (which is 9)") in a student's: "at(9) on a std::vector of 9 elements (0 to 8)".
std::string range_check_words(const std::string& what) {
  const std::string index_mark = "__n (which is ", size_mark = "this->size() (which is ";
  const auto index_at = what.find(index_mark), size_at = what.find(size_mark);
  if (what.find("_M_range_check") == std::string::npos || index_at == std::string::npos ||
      size_at == std::string::npos)
    return what;
  const auto number = [&what](std::size_t from) {
    return what.substr(from, what.find(')', from) - from);
  };
  const std::string index = number(index_at + index_mark.size());
  const std::string size = number(size_at + size_mark.size());
  return "at(" + index + ") on a std::vector of " + size + " elements: an index past the end";
}

// `function`: the task function that threw, named with its inputs in a standard exception's
// message, since the test that catches it sees only the message.
[[noreturn]] void rethrow_relayed(const std::exception_ptr& model_exception, const char* function) {
  const auto kind = Thrown(in->byte());
  const int task = int(in->integer());
  const std::string message = in->text(4096);
  switch (kind) {
    case Thrown::not_implemented:
      throw NotImplemented(message, task);
    case Thrown::step_failed:
      throw StepFailed(message);
    case Thrown::model:
      if (model_exception) std::rethrow_exception(model_exception);
      stop("the code says it passed on an error of the model, but the model raised none");
    case Thrown::standard: {
      // "TYPE\nWHAT" (recorder.cpp); a message without the line break is all what().
      const auto line_break = message.find('\n');
      const std::string type = line_break == std::string::npos ? "" : message.substr(0, line_break);
      const std::string what = range_check_words(
          line_break == std::string::npos ? message : message.substr(line_break + 1));
      throw_standard(type, "your " + std::string(function) +
                               (open_inputs.empty() ? "" : " (called with " + open_inputs + ")") +
                               " threw '" + what + "'");
    }
    case Thrown::other:
      throw ForeignException{};
  }
  stop("an exception of an unknown kind");
}

// Replays one call: its inputs' hash must match; callbacks are run on the harness's own model
// and must agree with the worker's; then the outputs are read into `outputs`.
// `columns`: how many particles the model's state holds (the step's own number).
// `described`: the inputs in words, for the feedback should the call crash or throw.
template <class Read>
void replay(Function f, std::uint64_t inputs, std::string described,
            const AccelerationFunction* model, Read read, Eigen::Index columns = -1) {
  if (failure) throw ReplayStopped(*failure);
  ++calls;
  open_call = name_of(f);
  open_inputs = std::move(described);
  waiting_since = std::chrono::steady_clock::now();
  struct Closed {
    ~Closed() { open_call = nullptr; }
  } closed;
  next({Event::call});
  const auto function = Function(in->byte());
  const auto hash = std::uint64_t(in->integer());
  if (function != f || hash != inputs)
    stop("call " + std::to_string(calls) + " of the task's functions was " + name_of(function) +
         (function == f ? " with other inputs" : "") + " in the run of your code, but " +
         name_of(f) + " in the test (does your code change an input it may only read?)");
  std::exception_ptr model_exception;
  for (;;) {
    switch (next({Event::callback, Event::result, Event::thrown})) {
      case Event::callback: {
        if (model == nullptr) stop(std::string(name_of(f)) + " called a model it was not given");
        Vectors r, v;
        in->get(r, columns);
        in->get(v, columns);
        try {
          const Vectors& a = (*model)(r, v);
          next({Event::callback_return});
          waiting_since = std::chrono::steady_clock::now();  // the code runs again from here
          if (std::uint64_t(in->integer()) != hash_of(a))
            stop("the model gave the code other accelerations than it gives the test");
        } catch (const ReplayStopped&) {
          throw;
        } catch (...) {
          model_exception = std::current_exception();
          next({Event::callback_throw});
        }
        break;
      }
      case Event::result:
        return read();
      default:
        rethrow_relayed(model_exception, name_of(f));
    }
  }
}

// Inputs in words, for the feedback: "r: 2x9" and the like.
std::string sized(const char* name, const Vectors& x) {
  return std::string(name) + ": 2x" + std::to_string(x.cols());
}

std::string grid(int rows, int cols) {
  return "rows = " + std::to_string(rows) + ", cols = " + std::to_string(cols);
}

Vec2 vec2() {
  Vec2 x;
  in->get(x);
  return x;
}

std::vector<Spring> springs() {
  std::vector<Spring> x;
  in->get(x);
  return x;
}

Vec2 spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  Vec2 f;
  replay(Function::spring_force, hash_of(r_p, r_q, k, rest_length), "", nullptr,
         [&] { f = vec2(); });
  return f;
}

Vec2 damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  Vec2 f;
  replay(Function::damper_force, hash_of(v_p, v_q, b), "", nullptr, [&] { f = vec2(); });
  return f;
}

void explicit_euler_step(const AccelerationFunction& a, double h, Vectors& r, Vectors& v) {
  replay(
      Function::explicit_euler_step, hash_of(h, r, v), sized("r and v", r), &a,
      [&] {
        in->get(r, r.cols());
        in->get(v, v.cols());
      },
      r.cols());
}

std::vector<Spring> structural_springs(int rows, int cols, const SpringFamilyParameters& p) {
  std::vector<Spring> s;
  replay(Function::structural_springs, hash_of(rows, cols, p), grid(rows, cols), nullptr,
         [&] { s = springs(); });
  return s;
}

void accumulate_spring_forces(const std::vector<Spring>& s, const Vectors& r, const Vectors& v,
                              Vectors& force) {
  replay(Function::accumulate_spring_forces, hash_of(s, r, v, force),
         std::to_string(s.size()) + " springs, " + sized("r, v and force", r), nullptr,
         [&] { in->get(force, force.cols()); });
}

std::vector<Spring> shear_springs(int rows, int cols, const SpringFamilyParameters& p) {
  std::vector<Spring> s;
  replay(Function::shear_springs, hash_of(rows, cols, p), grid(rows, cols), nullptr,
         [&] { s = springs(); });
  return s;
}

void verlet_step(const AccelerationFunction& a, double h, Vectors& r, Vectors& v,
                 VerletHistory& history) {
  replay(
      Function::verlet_step, hash_of(h, r, v, history), sized("r and v", r), &a,
      [&] {
        in->get(r, r.cols());
        in->get(v, v.cols());
        in->get(history, r.cols());
      },
      r.cols());
}

std::vector<Spring> bend_springs(int rows, int cols, const SpringFamilyParameters& p) {
  std::vector<Spring> s;
  replay(Function::bend_springs, hash_of(rows, cols, p), grid(rows, cols), nullptr,
         [&] { s = springs(); });
  return s;
}

void add_gravity(const Eigen::VectorXd& mass, const Vec2& g, Vectors& force) {
  replay(Function::add_gravity, hash_of(mass, g, force),
         "mass: " + std::to_string(mass.size()) + " entries, " + sized("force", force), nullptr,
         [&] { in->get(force, force.cols()); });
}

void add_wind(const WindField&, double t, const Vectors& r, const Vectors& v, Vectors& force) {
  replay(Function::add_wind, hash_of(t, r, v, force), sized("r, v and force", r), nullptr,
         [&] { in->get(force, force.cols()); });
}

void hold_pinned(const std::vector<bool>& pinned, Vectors& acceleration) {
  replay(Function::hold_pinned, hash_of(pinned, acceleration),
         "pinned: " + std::to_string(pinned.size()) + " entries, " +
             sized("acceleration", acceleration),
         nullptr, [&] { in->get(acceleration, acceleration.cols()); });
}

}  // namespace

Implementation replaying(TranscriptReader& reader) {
  in = &reader;
  return {"submission",
          0,
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

const std::optional<std::string>& replay_failure() {
  return failure;
}

const char* open_when_stopped() {
  return open_at_stop;
}

const std::string& inputs_when_stopped() {
  return inputs_at_stop;
}

std::optional<Awaited> awaited() {
  if (open_call == nullptr) return std::nullopt;
  return Awaited{
      open_call,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - waiting_since).count()};
}

void give_up(const std::string& why) {
  if (!failure) failure = why;
}

}  // namespace springlab::grading
