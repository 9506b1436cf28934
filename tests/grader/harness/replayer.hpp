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

}  // namespace springlab::grading
