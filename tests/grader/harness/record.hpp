// The harness's channel to the grader (tests/grader/src/verdict.cpp reads it). The grader sends
// a secret on fd 4; every record the harness writes on fd 3 starts with it, so output printed by
// the worker can never pass for a record. (The worker has neither descriptor: its fd 3 is the
// transcript.)
#pragma once

#include <string_view>

namespace springlab::grading {

inline constexpr int record_fd = 3;  ///< the harness writes its records here
inline constexpr int secret_fd = 4;  ///< the grader writes the secret here, then closes it

/// Reads the secret from secret_fd and closes it. Returns false if none arrived.
bool receive_secret();

/// Writes "<secret> <kind> <payload size>\n<payload>" to record_fd in one go.
void write_record(std::string_view kind, std::string_view payload);

}  // namespace springlab::grading
