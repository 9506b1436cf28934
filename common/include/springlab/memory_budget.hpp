// How much memory a run needs and how much the process may have: the guard validate() applies
// before anything of a grid is allocated.
#pragma once

#include "springlab/parameters.hpp"

#include <limits>
#include <string>

namespace springlab {

/// The memory a process may still allocate, and what limits it.
struct MemoryLimit {
  double bytes = 0.0;  ///< B
  std::string source;  ///< "physical memory", "ulimit -v", "ulimit -d" or "cgroup"
  /// What may still be mapped, resident or not (a thread's stack counts whole), B: the smaller of
  /// the ulimit -v and ulimit -d room, infinite when neither is set; and which of the two.
  double mappable = std::numeric_limits<double>::infinity();
  std::string mappable_source;
};

/// The smallest of: the physical memory still available (MemAvailable), RLIMIT_AS less the
/// address space in use (ulimit -v), RLIMIT_DATA less the data in use (ulimit -d), and the
/// process's cgroup limit less its usage (v2 memory.max, v1 memory.limit_in_bytes).
MemoryLimit available_memory();

/// The address space this process has mapped now (VmSize), B: what `ulimit -v` counts.
double address_space_in_use();

/// About how many bytes a run of scene p with p.integrator needs at its peak: the particles,
/// the springs, the simulation's buffers and the integrator's (for implicit Euler, its
/// conjugate gradients: the fallback's factorisation, needed only when they fail, checks its
/// own memory when it comes, see factorisation_bytes). From the data structures, checked against
/// the maximum resident size of springlab-run (memory_budget.cpp).
double estimated_bytes(const SceneParameters& p);

/// The stacks of the threads that share the work of a run of p beside the calling one, B:
/// thread_count() − 1 of them from the fast path's 2500 particles up, none below. Address space
/// that ulimit -v and ulimit -d count whole, of which little is ever resident.
double thread_stack_bytes(const SceneParameters& p);

/// One thread's stack as OpenMP's threads get it: OMP_STACKSIZE, else GOMP_STACKSIZE, read as
/// libgomp reads them (a whole number, then an optional unit B, K, M or G, K if none; spaces
/// around either), else the process's default stack (from ulimit -s); plus a guard page, B.
double one_thread_stack_bytes();

/// About how many bytes implicit Euler's fallback (a sparse LDLT of M + hC + h^2 K over
/// `free_particles` particles) needs beside the rest of the run.
double factorisation_bytes(double free_particles);

/// "about N MiB", for messages.
std::string mebibytes_text(double bytes);

/// Throws InvalidParameter (field "rows x cols") when estimated_bytes(p) exceeds limit.bytes,
/// or with the threads' stacks exceeds limit.mappable.
void check_memory(const SceneParameters& p, const MemoryLimit& limit);

/// What a std::bad_alloc during a run of p becomes: InvalidParameter (field "rows x cols") that
/// says when ("while building the scene", "at t = 0.5 s"), the estimate and the limit now.
[[noreturn]] void throw_out_of_memory(const SceneParameters& p, const std::string& when);

}  // namespace springlab
