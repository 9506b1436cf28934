// The verdict of one run of one test, from what the grader saw of the process: the harness's
// records count only when they carry the run's secret and the process then ended with status 0;
// anything else (an early exit, a crash, a signal, a limit, a forged line or file) is a failure,
// with its reason in words.
#pragma once

#include "words.hpp"  // without_raw_lines, signal_text

#include "process.hpp"

#include <string>

namespace springlab::grader {

struct RunVerdict {
  bool passed = false;
  std::string message;  ///< why it failed, for the student; "" when it passed
};

/// How the limits were set, to say so when one was hit.
struct LimitsText {
  std::string time;  ///< e.g. "10 times the reference's time, at least 2 s"
};

/// A fresh secret: 32 hex digits from the system's random source.
std::string new_secret();

RunVerdict judge(const Outcome& outcome, const std::string& secret, const Limits& limits,
                 const LimitsText& text);

/// The name of system call `number` on this machine ("openat"), or "number N".
std::string system_call_name(long number);

}  // namespace springlab::grader
