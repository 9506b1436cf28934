// What a student reads of a task's tests, in the same words wherever they ran: graded in the
// sandbox (springlab-grade's feedback.txt, ./lab test --student) or checked on the student's own
// machine where the grader cannot run (springlab-check: macOS, Windows). Text that student code
// could influence (its output, its messages) is made printable first: no terminal escapes,
// valid UTF-8.
#pragma once

#include "task_results.hpp"

#include <cstddef>
#include <string>

namespace springlab::grader {

/// The line that marks a hidden test in the feedback (instructors see it; students never do).
inline constexpr const char* hidden_mark = "(hidden test: students see it after the due date)";

/// Task `task`'s part of the feedback: a heading naming tasks/`folder`/, one line per test (a
/// hidden test's marked), the first failure of each failing test explained, and a closing count.
std::string task_text(const TaskResult& r, int task, const std::string& folder);

/// The task's line in the closing summary (after "  task N: "): all pass, not started (what to
/// write first), does not compile, or the count and the first failure; with the points.
std::string summary_line(const TaskResult& r);

/// The explanation of one failed test, then the first `shown` bytes of what its code printed.
std::string failure_text(const TestResult& t, std::size_t shown);

/// Points as people write them: "12", "2.5".
std::string points_text(double points);

/// `text` with control characters (but newlines and tabs) and invalid UTF-8 replaced by '?'.
std::string printable(const std::string& text);

/// A name (of a file, a folder) as printed anywhere: every control character, newlines and tabs
/// included, and every byte of invalid UTF-8 written \xNN, so that no name can make a line of
/// its own or move the terminal's cursor.
std::string escaped(const std::string& name);

/// How a test process that a signal ended is described ("crashed: " + this).
std::string signal_text(int signal);

/// Why a test process that did not finish failed, the same words for the grader and the check:
/// "timed out: stopped after 61 s (the limit is 60 s; an endless loop?)",
std::string timed_out_text(const std::string& after, const std::string& limit);
/// "printed more than 64 MB: stopped (printing inside a loop over every step?)",
std::string output_limit_text(long megabytes);
/// "exited before the test finished (exit status 1): does your code call exit(), ...?".
std::string early_exit_text(const std::string& status);

/// A failed assert() in `output` (Eigen's index and size checks, or the student's own), in a
/// student's words: which check, without the library's text or paths; "" when there is none.
std::string assertion_text(const std::string& output);

/// What a test's code printed without a failed assert()'s own line (and AddressSanitizer's note
/// of the signal it raised): the explanation has said it in a student's words.
std::string without_assertion_lines(const std::string& printed);

/// A failure's explanation without Catch2's own form of it (its "raw: " lines: file, line and
/// expression), which only whoever asks for it sees.
std::string without_raw_lines(const std::string& message);

}  // namespace springlab::grader
