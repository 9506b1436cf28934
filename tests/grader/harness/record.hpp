// The harness's side of the channel to the grader (tests/grader/src/protocol.hpp has the other).
// The grader sends a secret on fd 4 before any submission code is loaded; every record the
// harness writes on fd 3 starts with it, so output printed by a submission, or written to fd 3
// by it, can never pass for a record.
#pragma once

#include <string_view>

namespace springlab::grading {

inline constexpr int record_fd = 3;  ///< the harness writes its records here
inline constexpr int secret_fd = 4;  ///< the grader writes the secret here, then closes it

/// Reads the secret from secret_fd and closes it. Returns false if none arrived.
bool receive_secret();

/// Writes "<secret> <kind> <payload size>\n<payload>" to record_fd in one go.
void write_record(std::string_view kind, std::string_view payload);

/// The same, for a signal handler: writes "<secret> <kind> <number> 0\n" without allocating.
void write_record_from_signal(const char* kind, long number);

}  // namespace springlab::grading
