// The worker's side of the transcript (transcript.hpp): the graded task's functions as the
// submission defines them, each call written down as it happens.
#pragma once

#include "springlab/implementation.hpp"
#include "transcript.hpp"

namespace springlab::grading {

/// Functions that call those of `submission` and record each call to `out`; valid as long as
/// both are.
Implementation recording(const Implementation& submission, TranscriptWriter& out);

}  // namespace springlab::grading
