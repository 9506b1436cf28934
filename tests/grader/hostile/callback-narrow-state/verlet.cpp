// Attack on the harness's memory: the worker holds the transcript's descriptor (fd 3) and writes a
// transcript of its own: the call of verlet_step with the right input hash (the encoding of
// transcript.hpp, hashed with std::hash<std::string> as the harness does), then a call of the model
// with a state of ONE particle. The harness runs its own model on that state; for a Simulation's
// model (Simulation::acceleration) force_ gets one column and the reference spring forces then
// write force.col(p) for every particle p of the scene: past the end of the buffer, in the process
// that decides the verdict. Then _exit(0). No Verlet step is written: task 4 must get nothing, and
// the feedback must neither blame the kit nor show the harness's heap errors.
#include "springlab/task4_verlet.hpp"

// Declared by hand: the source policy refuses POSIX headers, but not a declaration (the sandbox
// and the test process's filter are what stop the call).
extern "C" long write(int, const void*, unsigned long);
extern "C" [[noreturn]] void _exit(int);

#include <cstdint>
#include <functional>
#include <string>

using namespace springlab;

namespace {

void raw(std::string& s, const void* p, std::size_t n) {
  s.append(static_cast<const char*>(p), n);
}
void put(std::string& s, std::int64_t x) {
  raw(s, &x, sizeof x);
}
void put(std::string& s, double x) {
  raw(s, &x, sizeof x);
}
void put(std::string& s, const Vectors& m) {
  put(s, std::int64_t(m.cols()));
  raw(s, m.data(), sizeof(double) * std::size_t(m.size()));
}

}  // namespace

void springlab::verlet_step(const AccelerationFunction&, double h, Vectors& r, Vectors& v,
                            VerletHistory& history) {
  std::string inputs;  // hash_of(h, r, v, history)
  put(inputs, h);
  put(inputs, r);
  put(inputs, v);
  inputs.push_back(char(history.has_previous));
  put(inputs, history.previous_position);
  std::string transcript;
  transcript.push_back(2);  // Event::call
  transcript.push_back(6);  // Function::verlet_step
  put(transcript, std::int64_t(std::hash<std::string>{}(inputs)));
  transcript.push_back(3);  // Event::callback: r, v of one particle
  const Vectors one = Vectors::Constant(2, 1, 0.5);
  put(transcript, one);
  put(transcript, one);
  [[maybe_unused]] const long written = ::write(3, transcript.data(), transcript.size());
  ::_exit(0);
}
