// How many threads the kit's own code uses: the fast force path of the reference model
// (grid_forces.hpp) and the integrators' vector work split large scenes over OpenMP threads.
// Student code never runs in a thread of ours. Results do not depend on the thread count's
// timing: every thread owns fixed rows of the grid and sums are combined in a fixed order, so a
// run repeated with the same count gives the same bits.
#pragma once

namespace springlab {

/// Threads the calling thread's later parallel work may use: 1 when OpenMP is not built in,
/// otherwise OpenMP's own choice (OMP_NUM_THREADS, or the cores the process may run on).
int thread_count();

/// Sets thread_count() for the calling thread only (OpenMP keeps it per thread), e.g. 1 in a
/// viewer's stepping thread so that it leaves the other core to drawing. Throws InvalidParameter
/// for n < 1.
void set_thread_count(int n);

/// Whether the kit was built with OpenMP (thread_count() can exceed 1).
bool parallel_built();

}  // namespace springlab
