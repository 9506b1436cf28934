// What the runner asks of the operating system, on POSIX systems (Linux, macOS) and Windows
// (issue 36): its peak memory, whether standard error is a terminal, and stopping on a signal.
#pragma once

namespace springlab::runner {

/// The most memory this process has had resident so far, MiB.
long peak_resident_mib();

/// Standard error is a terminal (progress then updates one line).
bool stderr_is_terminal();

/// Calls `on_signal` (which must be async-signal-safe) on Ctrl-C, and where the system has them
/// on SIGTERM and SIGHUP, once: a second signal ends the process. A signal ignored when the
/// program started (nohup) stays ignored. A write to a closed pipe is an error, not a signal.
void stop_on_signals(void (*on_signal)(int));

/// Writes `text` to standard error from a signal handler.
void write_stderr_in_handler(const char* text, unsigned long length);

/// "INT", "TERM", "HUP", or the number.
const char* signal_name(int signal);

}  // namespace springlab::runner
