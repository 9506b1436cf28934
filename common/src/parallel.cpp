#include "springlab/parallel.hpp"

#include "springlab/errors.hpp"

#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace springlab {

int thread_count() {
#ifdef _OPENMP
  return omp_get_max_threads();
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

}  // namespace springlab
