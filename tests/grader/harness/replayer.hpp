// The harness's side of the transcript (transcript.hpp): the graded task's functions, answered
// from what the worker recorded, each answer counted only for the very inputs the test gives.
#pragma once

#include "springlab/implementation.hpp"
#include "transcript.hpp"

#include <optional>
#include <string>

namespace springlab::grading {

/// Functions that answer from `in`; valid as long as it is.
Implementation replaying(TranscriptReader& in);

/// Why the replay gave up (the worker stopped, or its answers did not fit), if it did.
const std::optional<std::string>& replay_failure();

/// Marks the replay as given up; every further call throws ReplayStopped(why).
void give_up(const std::string& why);

/// The task function whose answer the replay waits for, and for how long, s: from the call, or
/// from the last answer to one of its callbacks. Nothing when no call is open.
struct Awaited {
  const char* function;
  double seconds;
};
std::optional<Awaited> awaited();

/// The task function whose answer was awaited when the replay stopped (the worker crashed, say,
/// inside it), or null.
const char* open_when_stopped();

/// That function's inputs in words ("rows = 1, cols = 2", "r and v: 2x9"), or "".
const std::string& inputs_when_stopped();

}  // namespace springlab::grading
