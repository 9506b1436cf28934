// Task 4: the Störmer–Verlet step with a central-difference velocity, (4.1)-(4.5).
// Every expectation comes from physics or from the theory of the method, computed here.
#include "springlab/task4_verlet.hpp"
#include "exception_names.hpp"
#include "lab_testing.hpp"
#include "probes.hpp"
#include "springlab/diagnostics.hpp"
#include "springlab/errors.hpp"
#include "springlab/this_implementation.hpp"

#include <cmath>
#include <sstream>
#include <string>

using namespace springlab;
using namespace springlab::testing;
using lab_catch::WithinAbs;
using lab_catch::WithinRel;

namespace {

// The damped oscillator a = -w2 r - c v, the same for every coordinate of every particle. It
// remembers the velocity of its last call, the v_n that the last (4.1) of a step saw.
struct LinearOscillator {
  LinearOscillator(double w2_, double c_) : w2(w2_), c(c_) {}
  double w2, c;
  long evaluations = 0;
  long endless = 0;  // > 0: this many evaluations in one test mean a loop that never stops
  Vectors storage, last_velocity;
  AccelerationFunction function() {
    return [this](const Vectors& r, const Vectors& v) -> const Vectors& {
      if (endless > 0 && evaluations >= endless) throw NeverStops{};
      ++evaluations;
      last_velocity = v;
      storage = -w2 * r - c * v;
      return storage;
    };
  }
  struct NeverStops {};
};

double largest(const Vectors& a) {
  return a.lpNorm<Eigen::Infinity>();
}

// The step (4.1)-(4.2) solves, exactly, for the oscillator: a = -w2 r - c v makes (4.1) with
// (4.2) linear in r_{n+1}:  (1 + h c/2) r_{n+1} = (2 - h² w2) r_n - (1 - h c/2) r_{n-1}.
Vectors solved_step(const LinearOscillator& o, double h, const Vectors& r,
                    const Vectors& r_previous) {
  const double q = h * o.c / 2.0;
  return ((2.0 - h * h * o.w2) * r - (1.0 - q) * r_previous) / (1.0 + q);
}

// The r_{-1} of (4.3) for the oscillator: r_0 - h v_0 + h²/2 a(r_0, v_0).
Vectors taylor_backwards(const LinearOscillator& o, double h, const Vectors& r0,
                         const Vectors& v0) {
  return r0 - h * v0 + 0.5 * h * h * (-o.w2 * r0 - o.c * v0);
}

// One step with the history already set (so not the first step, no (4.3)): r_{n-1}, r_n and a
// guess v for v_n that is off by a few tenths of a m/s, as a poor guess would be.
struct StepFrom {
  double h = 0.05;  // s
  Vectors r_previous = (Vectors(2, 2) << 1.0, -0.575, 0.3, 1.975).finished();
  Vectors r = (Vectors(2, 2) << 1.0, -0.5, 0.25, 2.0).finished();
  Vectors v = (r - r_previous) / h + (Vectors(2, 2) << 0.3, -0.2, 0.1, 0.4).finished();
  // Runs verlet_step on copies; `after` gets r_{n+1}, `v_after` the velocity handed back.
  void step(const AccelerationFunction& a, Vectors& after, Vectors& v_after,
            VerletHistory& history) const {
    after = r;
    v_after = v;
    history = {true, r_previous};
    verlet_step(a, h, after, v_after, history);
  }
};

// "name = (x, y; x, y)" for a failure message.
std::string shown(const std::string& name, const Vectors& m) {
  std::ostringstream out;
  out.precision(6);
  out << name << " = (";
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    out << (j ? "; " : "") << m(0, j) << ", " << m(1, j);
  out << ")";
  return out.str();
}

}  // namespace

TEST_CASE("Verlet (4.1): without dampers, r_{n+1} = 2 r_n - r_{n-1} + h^2 a(r_n)",
          "[task4][verlet][integrator]") {
  INFO("(4.1) r_{n+1} = 2 r_n - r_{n-1} + h^2 a(r_n, v_n); no dampers, history set (no (4.3))");
  LinearOscillator undamped{16.0, 0.0};
  const StepFrom s;
  Vectors r, v;
  VerletHistory history;
  try {
    s.step(undamped.function(), r, v, history);
  } catch (const StepFailed& failed) {
    // Without dampers a does not depend on v: every pass of (4.1)-(4.2) gives the same r_{n+1}
    // and v_n, so the second pass must settle. One that never does compares other values.
    // Measured, not a cause: comparing the wrong values and overwriting r_n during a pass (an
    // r_{n+1} that is a reference to r) both end here.
    FAIL("measured: verlet_step gave up (\""
         << failed.what() << "\") on a model without dampers, where every pass of (4.1)-(4.2) "
         << "gives the same v_n, so two successive estimates of (4.2)'s v_n agree on the second "
         << "pass: look at what your loop hands velocity_settled(...), and at whether a pass "
         << "changes r_n or r_{n-1} (it may write only r_{n+1})");
  }
  const Vectors a = -undamped.w2 * s.r;
  const Vectors expected = 2.0 * s.r - s.r_previous + s.h * s.h * a;
  const double error = largest(r - expected);
  CAPTURE(s.h, error);
  const bool h_for_h2 = largest(r - (2.0 * s.r - s.r_previous + s.h * a)) <= 1e-12;
  if (h_for_h2) UNSCOPED_INFO("r_{n+1} has h a where (4.1) has h^2 a");
  // Otherwise what probing the step shows: its coefficients of r_n, r_{n-1} and h^2 a.
  INFO((error > 1e-12 * largest(expected) && !h_for_h2
            ? probe_verlet_step(verlet_step_of(implementation()))
            : std::string()));
  CHECK(error <= 1e-12 * largest(expected));
}

TEST_CASE("Verlet (4.2): the dampers see the central difference, not the backward one",
          "[task4][verlet][integrator]") {
  INFO("(4.2) v_n = (r_{n+1} - r_{n-1}) / (2h) is the velocity in a(r_n, v_n) of (4.1)");
  LinearOscillator damped{16.0, 0.8};
  const StepFrom s;
  Vectors r, v;
  VerletHistory history;
  s.step(damped.function(), r, v, history);
  const Vectors backward = (s.r - s.r_previous) / s.h;
  REQUIRE(damped.evaluations > 0);
  // How far the velocity of the last evaluation of a is from the backward difference.
  const double from_backward = largest(damped.last_velocity - backward);
  CAPTURE(damped.evaluations);
  if (from_backward <= 1e-12 * largest(backward))
    UNSCOPED_INFO(
        "the dampers saw the backward difference (r_n - r_{n-1}) / h: that is first "
        "order and lowers the limit (4.5); (4.2) is the central (r_{n+1} - r_{n-1}) / "
        "(2h)");
  CHECK(from_backward > 1e-12 * largest(backward));
  // The velocity seen is the one that moved the particles: r_{n+1} is (4.1)'s with it.
  const Vectors moved =
      2.0 * s.r - s.r_previous + s.h * s.h * (-damped.w2 * s.r - damped.c * damped.last_velocity);
  INFO("compared: r_{n+1} with (4.1)'s 2 r_n - r_{n-1} + h^2 a(r_n, v_n), v_n the dampers' last");
  CHECK(largest(r - moved) <= 1e-12 * largest(s.r));
}

TEST_CASE("Verlet: with dampers, the iteration of section 4 makes (4.1) and (4.2) agree",
          "[task4][verlet][integrator]") {
  INFO(
      "(4.1) with (4.2): r_{n+1} = 2 r_n - r_{n-1} + h^2 a(r_n, v_n) where v_n = (r_{n+1} - "
      "r_{n-1}) / (2h) of the returned r_{n+1}");
  LinearOscillator damped{16.0, 0.8};
  const StepFrom s;
  const double h = s.h, q = h * damped.c / 2.0;
  Vectors r, v;
  VerletHistory history;
  s.step(damped.function(), r, v, history);
  // The exact solution (solved_step).
  const Vectors solved = solved_step(damped, h, s.r, s.r_previous);
  const Vectors v_solved = (solved - s.r_previous) / (2.0 * h);
  // Each pass of (4.1)-(4.2) shrinks the error of the guess for v_n by h c/2, exactly here. A
  // loop that stops at velocity_settled (1e-12 of the scale) has made it smaller than 1e-10 of
  // the scale, which takes at least `needed` evaluations from the guess s.v.
  const double scale = std::max(largest(v_solved), largest(s.r) / h);
  const double guess_error = largest(s.v - v_solved);
  const long needed = 1 + long(std::ceil(std::log(1e-10 * scale / guess_error) / std::log(q)));
  // (4.1) with the v_n of (4.2) from the r_{n+1} returned: what r_{n+1} must be.
  const Vectors central = (r - s.r_previous) / (2.0 * h);
  const Vectors consistent =
      2.0 * s.r - s.r_previous + h * h * (-damped.w2 * s.r - damped.c * central);
  const double gap = largest(r - consistent) / (h * h * damped.c);  // in v_n, m/s
  CAPTURE(h, q, damped.evaluations, needed, gap, largest(r - solved));
  const std::string loop = "the iteration of section 4 is missing or stops too early: ";
  // Why, worked out only once the check has failed: a diagnosis never changes a verdict.
  if (gap > 1e-10 * scale) {
    std::ostringstream why;
    // The first two are measured exactly (the velocity the dampers saw), the third probed.
    if (largest(damped.last_velocity - s.v) <= 1e-12 * scale)
      why << "likely mistake: " << loop
          << "(4.1) used the velocity passed in (the guess) and the v_n of (4.2) never "
          << "went back into a(r_n, v_n); repeat (4.1) and (4.2) until velocity_settled(...)";
    else if (largest(damped.last_velocity - (s.r - s.r_previous) / h) <= 1e-12 * scale)
      why << "likely mistake: the dampers saw the backward difference (r_n - r_{n-1}) / h, not "
             "(4.2)'s central "
          << "(r_{n+1} - r_{n-1}) / (2h)";
    else if (const std::string probed = probe_verlet_step(verlet_step_of(implementation()));
             probed.rfind("likely mistake: ", 0) == 0)
      why << probed;  // a wrong formula, run on every probe: what the step solves
    else {
      // No cause checked: too few passes and a wrong (4.2) both leave a gap. What was measured.
      why << "measured: after " << damped.evaluations << " evaluations of a, the v_n in (4.1) is "
          << gap << " m/s away from (4.2)'s (r_{n+1} - r_{n-1}) / (2h)";
      if (damped.evaluations < needed)
        why << ", where a loop that repeats (4.1) and (4.2) until velocity_settled(...) takes at "
            << "least " << needed << " from this guess";
      if (!probed.empty()) why << "; " << probed.substr(probed.find(": ") + 2);
      why << ": look at (4.2) in your loop and at when the loop stops";
    }
    UNSCOPED_INFO(why.str());
  }
  CHECK(gap <= 1e-10 * scale);
  if (damped.evaluations < needed)
    UNSCOPED_INFO(loop << damped.evaluations << " evaluations of a, where a guess " << guess_error
                       << " m/s off needs at least " << needed
                       << " passes to settle at h c / 2 = " << q);
  CHECK(damped.evaluations >= needed);
}

TEST_CASE("Verlet (4.3): the first step makes r_{-1} by a Taylor step backwards",
          "[task4][verlet][integrator]") {
  INFO("(4.3) r_{-1} = r_0 - h v_0 + h^2/2 a(r_0, v_0), made when history.has_previous is false");
  // a(r_0, v_0) = a0 on the first call, the one (4.3) needs; zero on every later call, so that
  // (4.1) gives r_1 = 2 r_0 - r_{-1} whatever else the step does, and r_{-1} = 2 r_0 - r_1.
  const double h = 0.05;
  const Vectors r0 = (Vectors(2, 2) << 1.0, -0.5, 0.25, 2.0).finished();
  const Vectors v0 = (Vectors(2, 2) << 0.0, 1.5, -1.0, 0.5).finished();
  const Vectors a0 = (Vectors(2, 2) << -16.0, 8.0, -4.0, -32.0).finished();
  long calls = 0;
  Vectors storage, first_r, first_v;
  const AccelerationFunction model = [&](const Vectors& r, const Vectors& v) -> const Vectors& {
    if (calls++ == 0) first_r = r, first_v = v;
    storage = calls == 1 ? a0 : Vectors(Vectors::Zero(2, 2));
    return storage;
  };
  Vectors r = r0, v = v0;
  VerletHistory history;
  verlet_step(model, h, r, v, history);
  REQUIRE(calls > 0);
  if (!history.has_previous)
    UNSCOPED_INFO(
        "likely mistake: after the first step history.has_previous is still false, so the "
        "next step makes r_{-1} by (4.3) again instead of using the r_n the history "
        "keeps; the first step must set it to true");
  CHECK(history.has_previous);
  const double first_call_off = std::max(largest(first_r - r0), largest(first_v - v0));
  if (first_call_off > 0.0)
    UNSCOPED_INFO(
        "likely mistake: the first evaluation of a was not (4.3)'s a(r_0, v_0), with the r and v "
        "passed in");
  CHECK(first_call_off == 0.0);
  const Vectors yours = 2.0 * r0 - r;
  const Vectors expected = r0 - h * v0 + 0.5 * h * h * a0;
  const auto is = [&](const Vectors& candidate) {
    return largest(yours - candidate) <= 1e-12 * largest(r0);
  };
  std::string why;
  if (is(r0 - h * v0)) why = "the h^2/2 a(r_0, v_0) term of (4.3) is missing";
  if (is(r0 + h * v0 + 0.5 * h * h * a0) || is(r0 + h * v0))
    why = "(4.3) steps forwards in time: r_{-1} is one step back, r_0 - h v_0 + ...";
  // r_1 = r_0 is also a step that returned before stepping: the velocity tells them apart
  // ((4.4) gives 0 after a start at rest; a step not taken leaves v_0).
  if (is(r0) && largest(v) <= 1e-12 * largest(r0) / h)
    why = "r_{-1} = r_0, as if at rest: make r_{-1} by (4.3)";
  if (is(r0) && largest(v - v0) == 0.0 && largest(v0) > 0.0)
    why =
        "the first step returned r and v as they were passed in (r_1 = r_0, v_1 = v_0): it "
        "took no step; after making r_{-1} by (4.3) the first step still takes (4.1)";
  const double error = largest(yours - expected);
  CAPTURE(h, error);
  if (!is(expected)) {
    UNSCOPED_INFO("r_{-1} (seen through (4.1) as 2 r_0 - r_1): " << shown("yours", yours) << ", "
                                                                 << shown("(4.3)", expected));
    UNSCOPED_INFO((why.empty() ? probe_verlet_step(verlet_step_of(implementation()))
                               : "likely mistake: " + why));
  }
  CHECK(error <= 1e-12 * largest(r0));
}

TEST_CASE("Verlet (4.4): the velocity handed back is the second-order backward difference",
          "[task4][verlet][integrator]") {
  INFO("(4.4) v_{n+1} = (3 r_{n+1} - 4 r_n + r_{n-1}) / (2h), with the r_{n+1} the step returns");
  LinearOscillator damped{16.0, 0.8};
  const StepFrom s;
  Vectors r, v;
  VerletHistory history;
  s.step(damped.function(), r, v, history);
  const Vectors expected = (3.0 * r - 4.0 * s.r + s.r_previous) / (2.0 * s.h);
  const auto is = [&](const Vectors& candidate) {
    return largest(v - candidate) <= 1e-10 * largest(expected);
  };
  std::string why;
  if (largest(v - s.v) == 0.0) why = "v still holds the velocity passed in: set it by (4.4)";
  if (is((r - s.r) / s.h)) why = "v is the first-order (r_{n+1} - r_n) / h; (4.4) is second order";
  if (is((r - s.r_previous) / (2.0 * s.h)))
    why = "v is (4.2)'s v_n, the velocity at t_n; hand back (4.4)'s, at t_{n+1}";
  const double error = largest(v - expected);
  CAPTURE(s.h, error);
  if (!is(expected)) {
    UNSCOPED_INFO("v handed back: " << shown("yours", v) << ", " << shown("(4.4)", expected));
    UNSCOPED_INFO((why.empty() ? probe_verlet_step(verlet_step_of(implementation()))
                               : "likely mistake: " + why));
  }
  CHECK(error <= 1e-10 * largest(expected));
}

TEST_CASE("Verlet: after a step the history holds r_n, the r_{n-1} of the next step",
          "[task4][verlet][integrator]") {
  INFO("step 4 of section 4: history.previous_position = r_n and has_previous = true");
  LinearOscillator damped{16.0, 0.8};
  const AccelerationFunction model = damped.function();
  Vectors r = Vectors::Constant(2, 3, 0.5), v = Vectors::Constant(2, 3, -0.25);
  VerletHistory history;
  const Vectors r0 = r, v0 = v;
  verlet_step(model, 0.01, r, v, history);
  {
    // The history of a step that moved: r_1 from (4.3) and (4.1)-(4.2) solved.
    INFO("compared: r_1 with the step (4.3), (4.1), (4.2) solve from r_0 and v_0");
    const Vectors r1 = solved_step(damped, 0.01, r0, taylor_backwards(damped, 0.01, r0, v0));
    CHECK(largest(r - r1) <= 1e-10 * largest(r0));
  }
  INFO((history.has_previous && history.previous_position.cols() == r0.cols() &&
                largest(history.previous_position - r0) == 0.0
            ? std::string()
            : probe_verlet_step(verlet_step_of(implementation()))));
  CHECK(history.has_previous);
  CHECK(largest(history.previous_position - r0) == 0.0);
  const Vectors r1 = r;
  verlet_step(model, 0.01, r, v, history);
  CHECK(largest(history.previous_position - r1) == 0.0);
}

TEST_CASE("Verlet: without dampers a step needs only two evaluations",
          "[task4][verlet][integrator]") {
  INFO("(4.1)-(4.2) without dampers: a does not depend on v_n, so the second pass agrees");
  Vectors r = Vectors::Constant(2, 3, 0.5), v = Vectors::Constant(2, 3, -0.25);
  VerletHistory history;
  LinearOscillator undamped{16.0, 0.0};
  const AccelerationFunction plain = undamped.function();
  const Vectors r0 = r;
  verlet_step(plain, 0.01, r, v, history);  // the first step adds one evaluation, for (4.3)
  const long first = undamped.evaluations;
  const Vectors r1 = r;
  verlet_step(plain, 0.01, r, v, history);
  CAPTURE(undamped.evaluations - first);
  CHECK(undamped.evaluations - first <= 2);
  // Two evaluations for a step that moved as (4.1) says: r_2 = 2 r_1 - r_0 - h² w2 r_1.
  INFO("compared: r_2 with (4.1)'s 2 r_1 - r_0 + h^2 a(r_1)");
  CHECK(largest(r - solved_step(undamped, 0.01, r1, r0)) <= 1e-12 * largest(r1));
}

TEST_CASE("Verlet: with dampers a step needs only a few evaluations",
          "[task4][verlet][integrator]") {
  INFO(
      "each pass of (4.1)-(4.2) shrinks the error of v_n by h c / 2: from the guess (4.4) "
      "made, a few passes reach velocity_settled");
  Vectors r = Vectors::Constant(2, 3, 0.5), v = Vectors::Constant(2, 3, -0.25);
  VerletHistory history;
  LinearOscillator undamped{16.0, 0.0};
  verlet_step(undamped.function(), 0.01, r, v, history);
  const Vectors r1 = r;
  verlet_step(undamped.function(), 0.01, r, v, history);
  const Vectors r2 = r;
  LinearOscillator damped{16.0, 1.0};
  verlet_step(damped.function(), 0.01, r, v, history);
  // From a guess good to about h^2 the estimates reach the 1e-12 of velocity_settled in
  // log(1e-12 / h^2) / log(h c / 2) passes, plus one that confirms it and one to spare.
  const double passes = std::ceil(std::log(1e-12 / (0.01 * 0.01)) / std::log(0.01 * 1.0 / 2)) + 2;
  CAPTURE(damped.evaluations, passes);
  CHECK(double(damped.evaluations) <= passes);
  // A few evaluations for a step that reached (4.1)-(4.2)'s r_3.
  INFO("compared: r_3 with the one (4.1) and (4.2) solved together give");
  CHECK(largest(r - solved_step(damped, 0.01, r2, r1)) <= 1e-10 * largest(r2));
}

TEST_CASE("Verlet: a step that cannot settle is reported, not turned into NaN",
          "[task4][verlet][stability]") {
  INFO(
      "verlet_max_iterations: (4.1)-(4.2) settle only while h c / 2 < 1; after that many "
      "passes verlet_step throws StepFailed");
  LinearOscillator overdamped{1.0, 1000.0};
  overdamped.endless = 100 * verlet_max_iterations;  // far beyond any cap
  const AccelerationFunction model = overdamped.function();
  Vectors r = Vectors::Constant(2, 2, 1.0), v = Vectors::Constant(2, 2, 1.0);
  VerletHistory history;
  // The first step's guess, v_0, already solves (4.1)-(4.2) exactly, so that step settles and
  // moves to the r_1 they solve; it is the second that must iterate, and fail.
  const Vectors r0 = r, v0 = v;
  const Vectors r1 = solved_step(overdamped, 0.01, r0, taylor_backwards(overdamped, 0.01, r0, v0));
  bool first_done = false, first_moved = false, step_failed = false;
  long before = 0;  // evaluations before the step that fails
  std::ostringstream why, why_first;
  try {
    verlet_step(model, 0.01, r, v, history);
    first_done = true;
    before = overdamped.evaluations;
    first_moved = largest(r - r1) <= 1e-10 * largest(r0);
    if (!first_moved)
      why_first << "the first step, which settles at once (v_0 solves (4.1)-(4.2)), did not move r "
                << "to the r_1 of (4.3), (4.1) and (4.2)";
    verlet_step(model, 0.01, r, v, history);
    why << "no StepFailed: h c / 2 = 5, the passes cannot settle, yet the step returned";
  } catch (const StepFailed&) {
    step_failed = true;
    if (!first_done)
      why_first << "StepFailed already in the first step, whose guess settles at once";
  } catch (const LinearOscillator::NeverStops&) {
    why << "the iteration has no cap: " << overdamped.evaluations << " evaluations in one step "
        << "and still going; stop after verlet_max_iterations = " << verlet_max_iterations
        << " passes and throw StepFailed";
  } catch (...) {
    // The test expects StepFailed: any other type is named beside it.
    why << "the step threw " << current_exception_text() << " where the test expects StepFailed "
        << "(springlab/errors.hpp), the type the simulation reports as a step that failed";
  }
  CAPTURE(overdamped.evaluations);
  if (!step_failed) UNSCOPED_INFO(why.str());
  CHECK(step_failed);
  if (!first_moved) UNSCOPED_INFO(why_first.str());
  CHECK(first_moved);
  // Each pass costs one evaluation of a: a step that gives up after verlet_max_iterations passes
  // has made exactly that many, no more and no fewer.
  if (step_failed && first_done) {
    const long passes = overdamped.evaluations - before;
    INFO(
        "compared: the evaluations of a in the step that threw StepFailed, with "
        "verlet_max_iterations = "
        << verlet_max_iterations << " (one a pass)");
    CHECK(passes == long(verlet_max_iterations));
  }
}

TEST_CASE("Verlet: a strongly damped step that needs dozens of passes still settles",
          "[task4][verlet][stability]") {
  INFO(
      "verlet_max_iterations: while h c / 2 < 1 the passes of (4.1)-(4.2) settle, some steps "
      "only after dozens of them; verlet_step gives up only after verlet_max_iterations");
  // h c / 2 = 0.6: each pass shrinks the error of v_n by 0.6, so from StepFrom's guess the
  // passes reach velocity_settled (1e-12 of the scale) only after `needed` of them, well
  // beyond a handful and well within verlet_max_iterations.
  const StepFrom s;
  LinearOscillator damped{16.0, 1.2 / s.h};
  const double q = s.h * damped.c / 2.0;
  const Vectors solved = solved_step(damped, s.h, s.r, s.r_previous);
  const Vectors v_solved = (solved - s.r_previous) / (2.0 * s.h);
  const double scale = std::max(largest(v_solved), largest(s.r) / s.h);
  const long needed =
      long(std::ceil(std::log(1e-12 * scale / largest(s.v - v_solved)) / std::log(q)));
  REQUIRE(needed > 20);
  REQUIRE(needed < verlet_max_iterations);
  Vectors r, v;
  VerletHistory history;
  bool returned = false;
  std::string why;
  try {
    s.step(damped.function(), r, v, history);
    returned = true;
  } catch (const StepFailed&) {
    std::ostringstream text;
    text << "verlet_step threw StepFailed after " << damped.evaluations
         << " evaluations of a, where h c / 2 = " << q << " settles after about " << needed
         << " passes: give up only after verlet_max_iterations = " << verlet_max_iterations;
    why = text.str();
  } catch (...) {
    why = "verlet_step threw " + current_exception_text() + " on a step that settles";
  }
  CAPTURE(q, needed, damped.evaluations);
  if (!returned) UNSCOPED_INFO(why);
  REQUIRE(returned);
  INFO("compared: r_{n+1} with the one (4.1) and (4.2) solved together give");
  CHECK(largest(r - solved) <= 1e-10 * largest(s.r));
}

TEST_CASE("Verlet converges with order 2 to the exact two-mass solution",
          "[task4][verlet][order]") {
  INFO(
      "order 2 (section 4): against the exact two-mass solution the errors of position and "
      "velocity shrink 4x when h halves");
  const SceneParameters lab;  // the lab's values
  const TwoMassExact exact{lab.structural.k, lab.structural.b, lab.mass, 0.2};
  std::vector<double> position_errors, velocity_errors;
  for (double h : {0.01, 0.005, 0.0025}) {
    Simulation sim(two_masses(lab.structural.k, lab.structural.b, lab.mass, exact.u0, h, "verlet"),
                   implementation());
    double position_error = 0.0, velocity_error = 0.0;
    run(sim, std::lround(2.0 / h), [&](const Simulation& s) {
      const Vectors& v = s.particles().velocity;
      position_error = std::max(position_error, std::abs(stretch_of(s) - exact.stretch(s.time())));
      velocity_error =
          std::max(velocity_error, std::abs(v(0, 1) - v(0, 0) - exact.stretch_rate(s.time())));
    });
    position_errors.push_back(position_error);
    velocity_errors.push_back(velocity_error);
  }
  CAPTURE(position_errors, velocity_errors);
  for (std::size_t i = 0; i + 1 < position_errors.size(); ++i) {
    CHECK_THAT(observed_order(position_errors[i], position_errors[i + 1]), WithinAbs(2.0, 0.15));
    CHECK_THAT(observed_order(velocity_errors[i], velocity_errors[i + 1]), WithinAbs(2.0, 0.15));
  }
}

TEST_CASE("Verlet: momentum is conserved over thousands of steps", "[task4][verlet][momentum]") {
  INFO("no net internal force, so sum m_i (r_{n+1} - 2 r_n + r_{n-1}) = 0 and P stays constant");
  Scene scene = build_scene(task_scene(4), implementation());
  randomise(scene.particles, 0.2, 0.8, 71);
  Simulation sim(std::move(scene), implementation());
  const Vec2 start = sim.diagnostics().momentum;
  REQUIRE(start.norm() > 0.1);
  const auto centre = [](const Particles& p) -> Vec2 { return p.position * p.mass / p.mass.sum(); };
  const Vec2 centre_start = centre(sim.particles());
  const double worst = momentum_drift(sim, 6000);
  CAPTURE(start, worst);
  CHECK(worst <= 1e-11);
  // P held by a system that moves: its centre of mass went on at P / M all along (sum m_i times
  // (4.1) is C_{n+1} - 2 C_n + C_{n-1} = 0, and (4.3) starts it at v_0).
  const Vec2 travelled = sim.time() * start / sim.particles().mass.sum();
  CAPTURE(travelled);
  CHECK_THAT(Vec2(centre(sim.particles()) - centre_start),
             IsNear(travelled, 1e-9 * travelled.norm()));
}

TEST_CASE("Verlet: a mirror-symmetric start moves mirror-symmetrically", "[task4][symmetry]") {
  INFO("the 3x3 grid mirrored left-right about x = 1 mirrors its motion");
  const int n = 3;
  Scene scene = build_scene(task_scene(4), implementation());
  Vectors& r = scene.particles.position;
  r = build_scene(lab_grid(n, n, true, 0.01, "verlet"), implementation()).particles.position;
  r.col(at(0, 1, n)) += Vec2(0.0, 0.3);  // the top middle pulled up
  r.col(at(2, 0, n)) += Vec2(-0.1, -0.1);
  r.col(at(2, 2, n)) += Vec2(0.1, -0.1);
  const double pulled = r(1, at(0, 1, n));
  Simulation sim(std::move(scene), implementation());
  double worst = 0.0, lowest = pulled;
  run(sim, 3000, [&](const Simulation& s) {
    const Vectors& p = s.particles().position;
    lowest = std::min(lowest, p(1, at(0, 1, n)));
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        const Vec2 a = p.col(at(row, col, n)), b = p.col(at(row, n - 1 - col, n));
        worst = std::max({worst, std::abs(a.x() + b.x() - 2.0), std::abs(a.y() - b.y())});
      }
  });
  CAPTURE(worst, pulled, lowest);
  CHECK(worst <= 1e-10);
  CHECK(lowest < pulled);  // the springs pulled the top middle back down: it moved
}

TEST_CASE("Verlet is stable at the lab step on the 3x3 grid for 60 s",
          "[task4][verlet][stability]") {
  INFO("(4.5): h = 0.01 s is far below 2/w_max for the 3x3 lab grid; the dampers calm it down");
  Simulation sim(task_scene(4), implementation());
  const double start = sim.diagnostics().total();
  double early = 0.0, late = 0.0;
  const long steps = 6000;
  REQUIRE_NOTHROW(run(sim, steps, [&](const Simulation& s) {
    const double strain = largest_strain(s.scene().springs, s.particles().position);
    if (s.steps_taken() <= steps / 10) early = std::max(early, strain);
    if (s.steps_taken() > 9 * steps / 10) late = std::max(late, strain);
  }));
  CAPTURE(start, sim.diagnostics().total(), early, late);
  CHECK_THAT(sim.time(), WithinRel(60.0, 1e-12));
  CHECK(sim.diagnostics().total() < start);
  CHECK(late < early);
}

TEST_CASE("Verlet: stable just below 2/w_max, unstable just above", "[task4][verlet][stability]") {
  INFO("(4.5): the central-difference Verlet step is stable for h < 2/w_max whatever the damping");
  const SceneParameters p = task_scene(4);
  const double limit = verlet_critical_step(linearise_at_rest(p, implementation()));
  const double factor = GENERATE(0.9, 1.1);
  Scene scene = perturbed_at_rest(p, implementation(), 1e-9, 8);
  const double start = strain_norm(scene.springs, scene.particles.position);
  scene.parameters.step = factor * limit;
  const long steps = 4000;
  const std::vector<double> history =
      strain_history(std::move(scene), implementation(), steps, 0.0, 1e3 * start);
  // Empty when the very first step gave no number: nothing to read at its end.
  const double last = history.empty() ? std::nan("") : history.back();
  CAPTURE(limit, factor, start, history.size(), last);
  std::ostringstream at;
  at.precision(3);
  at << "h = " << factor << "·2/ω_max = " << factor * limit << " s (ω_max = " << 2.0 / limit
     << " rad/s)";
  const long samples = long(history.size());
  if (factor < 1.0) {
    if (samples < steps)
      UNSCOPED_INFO("diverged after " << samples << " of " << steps << " steps at " << at.str()
                                      << ": (4.5) says Verlet is stable below 2/ω_max");
    CHECK(samples == steps);  // never grew a thousandfold
    if (!(last < start))
      UNSCOPED_INFO("not calmed at " << at.str() << ": the deformation went from " << start
                                     << " to " << last << " m in " << samples << " steps");
    CHECK(last < start);  // the dampers won
  } else {
    // Beyond the limit the highest mode grows by x2.4 a step: a thousandfold within 10 steps.
    if (samples >= 200)
      UNSCOPED_INFO("still bounded after " << samples << " steps at " << at.str()
                                           << ": beyond 2/ω_max (4.5) the fastest mode grows");
    CHECK(samples < 200);
  }
}
