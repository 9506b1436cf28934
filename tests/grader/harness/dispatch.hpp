// One table through which every call of a task function goes, in the harness and the worker alike:
// the tests' calls (forwarders.cpp), the reference code's calls of other tasks' functions and the
// submission's (dispatchers.inc). The table holds the kit's reference for every task but the one
// graded, and for that one the recording functions (worker) or the replaying ones (harness).
#pragma once

#include "springlab/implementation.hpp"

/// The table in use (defined by dispatch.cpp in the programs, by entry.cpp in each submission
/// library, which points it at its host's).
extern "C" const springlab::Implementation* springlab_dispatch;

namespace springlab::grading {

/// Called once per task, at start-up, by the reference code of that task (registrar.cpp).
void register_reference(int task, const Implementation& table);

/// Copies the functions of task `task` (1-5) from `from` into `into`.
void take_task(Implementation& into, const Implementation& from, int task);

/// The reference of every task linked into this program, with task `graded` taken from
/// `graded_functions`; becomes the table in use.
void use_table(int graded, const Implementation& graded_functions);

}  // namespace springlab::grading
