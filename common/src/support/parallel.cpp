#include "springlab/parallel.hpp"

#include "springlab/errors.hpp"

#include <algorithm>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace springlab {

int thread_count() {
#ifdef _OPENMP
  // OMP_NUM_THREADS can ask for any number; the kit's rows gain nothing past a few threads a
  // processor, and libgomp's team start data on the calling thread's stack overflows it near
  // 70,000 (a segmentation fault): at most max_threads().
  return std::min(omp_get_max_threads(), max_threads());
#else
  return 1;
#endif
}

int max_threads() {
#ifdef _OPENMP
  return std::max(8, 4 * omp_get_num_procs());
#else
  return 1;
#endif
}

void set_thread_count(int n) {
  if (n < 1) throw InvalidParameter("threads", std::to_string(n), "threads >= 1");
#ifdef _OPENMP
  omp_set_num_threads(n);
#endif
}

bool parallel_built() {
#ifdef _OPENMP
  return true;
#else
  return false;
#endif
}

bool splits(long n) {
  return n >= parallel_items && thread_count() > 1;
}

namespace detail {

void run_blocks(long n, BlockBody call, void* body) {
  const int threads = n >= parallel_items ? thread_count() : 1;
  if (threads == 1) {
    call(body, 0, n);
    return;
  }
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
  {
    const long t = omp_get_thread_num(), granted = omp_get_num_threads();
    call(body, n * t / granted, n * (t + 1) / granted);
  }
#endif
}

double add_blocks(long n, double (*call)(void* term, long begin, long end), void* term) {
  if (n <= sum_block) return call(term, 0, n);
  const long blocks = (n + sum_block - 1) / sum_block;
  // Allocated here, not in the threads (see grid_forces.cpp: a thread's malloc arena).
  std::vector<double> sums(std::size_t(blocks), 0.0);
  const auto block = [&](long b) {
    sums[std::size_t(b)] = call(term, b * sum_block, std::min(n, (b + 1) * sum_block));
  };
  [[maybe_unused]] const int threads = n >= parallel_items ? thread_count() : 1;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
#endif
  for (long b = 0; b < blocks; ++b)
    block(b);
  double total = 0.0;
  for (const double s : sums)
    total += s;
  return total;
}

}  // namespace detail

}  // namespace springlab
