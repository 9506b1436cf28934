// What a test process may do once it holds a submission's code: compute, allocate, print, read
// files and end. It may not write, rename or delete files, start programs or threads, signal
// other processes, open network connections, raise its limits or trace anything. Enforced by the
// kernel (seccomp filters), so no code in the process can lift it.
#pragma once

namespace springlab::grading {

/// Installs the filters. Opening a file for writing fails with EACCES (code that tries to log to
/// a file still runs); any other forbidden system call raises SIGSYS, whose handler records its
/// number for the grader and ends the process. Returns false (errno set) if the kernel refused.
bool forbid_what_tests_never_need();

/// After the submission's library is loaded: no memory may become executable any more, so no
/// other code (another library, code built at run time) can be run.
bool forbid_new_code();

}  // namespace springlab::grading
