// What a test process may do once it holds a submission's code: compute, allocate, print, read
// files and end. It may not write, rename or delete files, start programs or threads, signal
// other processes, open network connections, raise its limits or trace anything. Enforced by the
// kernel (seccomp filters), so no code in the process can lift it.
#pragma once

#include <string>

namespace springlab::grading {

/// Where the kernel has Landlock (Linux 5.13 and later): from now on the process may read only
/// the system's files (/usr, /lib, /etc, /proc, /sys, /dev/null, /dev/urandom), `program` and
/// `library`, and write none; so no other submission's copy, no other library and nothing of the
/// kit can be read. Returns false where the kernel has no Landlock (the other checks remain).
bool read_only_what_tests_need(const std::string& program, const std::string& library);

/// The executable memory of this process outside the system's libraries, `program` and
/// `library` ("" when there is none): code a submission loaded or built that is not its own.
std::string foreign_code(const std::string& program, const std::string& library);

/// Installs the system-call filters; `on_forbidden(number)` is called (in a signal handler)
/// before the process ends at a forbidden call. Opening a file for writing fails with EACCES (code
/// that tries to log to a file still runs); any other forbidden system call raises SIGSYS, whose
/// handler records its number for the grader and ends the process. Returns false (errno set) if the
/// kernel refused.
bool forbid_what_tests_never_need(void (*on_forbidden)(long number));

/// After the submission's library is loaded: no memory may become executable any more, so no
/// other code (another library, code built at run time) can be run.
bool forbid_new_code();

}  // namespace springlab::grading
