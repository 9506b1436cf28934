// How many threads the kit's own code uses: the fast force path of the reference model
// (grid_forces.hpp) and the integrators' vector work split large scenes over OpenMP threads.
// Student code never runs in a thread of ours. Results do not depend on the thread count's
// timing: every thread owns fixed rows of the grid and sums are combined in a fixed order, so a
// run repeated with the same count gives the same bits.
#pragma once

namespace springlab {

/// Threads the calling thread's later parallel work may use: 1 when OpenMP is not built in,
/// otherwise OpenMP's own choice (OMP_NUM_THREADS, or the cores the process may run on), at most
/// max_threads().
int thread_count();

/// The most threads the kit uses, whatever OMP_NUM_THREADS asks: four per processor, at least 8.
int max_threads();

/// Sets thread_count() for the calling thread only (OpenMP keeps it per thread), e.g. 1 in a
/// viewer's stepping thread so that it leaves the other core to drawing. Throws InvalidParameter
/// for n < 1.
void set_thread_count(int n);

/// Whether the kit was built with OpenMP (thread_count() can exceed 1).
bool parallel_built();

/// Below this many particles the fast force path (grid_forces.hpp) runs on one thread, faster
/// than two (a parallel region costs a few microseconds; a 50 × 50 fabric's forces about 40).
inline constexpr int parallel_force_particles = 2500;

/// Below this many items (particles, springs) a pass runs on one thread: starting threads costs
/// a few microseconds, as much as a pass over some 10,000 particles.
inline constexpr long parallel_items = 16384;

/// Whether for_blocks over n items runs on more than one thread (from parallel_items up, with
/// thread_count() > 1): for work that must then take another shape, e.g. gather instead of scatter.
bool splits(long n);

/// The items a sum_blocks term adds up at a time: fixed, so the blocks and the order in which
/// their sums are added do not depend on the thread count.
inline constexpr long sum_block = 8192;

namespace detail {
using BlockBody = void (*)(void* body, long begin, long end);
void run_blocks(long n, BlockBody call, void* body);
double add_blocks(long n, double (*call)(void* term, long begin, long end), void* term);
}  // namespace detail

/// Calls body(begin, end) on consecutive blocks that cover [0, n) exactly once, one block per
/// thread (thread_count() of them from parallel_items up). For element-wise work, whose result
/// does not depend on the split.
template <typename Body>
void for_blocks(long n, Body&& body) {
  detail::run_blocks(
      n, [](void* b, long begin, long end) { (*static_cast<Body*>(b))(begin, end); }, &body);
}

/// The sum of term(begin, end) over the blocks [0, sum_block), [sum_block, 2 sum_block), … of
/// [0, n), added in that order: the same bits for any number of threads, and for n ≤ sum_block
/// exactly term(0, n).
template <typename Term>
double sum_blocks(long n, Term&& term) {
  return detail::add_blocks(
      n, [](void* t, long begin, long end) { return (*static_cast<Term*>(t))(begin, end); }, &term);
}

}  // namespace springlab
