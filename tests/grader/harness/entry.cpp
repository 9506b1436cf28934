// Compiled into every submission library: the library's own pointer to the table in use, and
// the one function the worker looks up after loading it, which points that pointer at the
// worker's table and returns the library's own task functions.
#include "dispatch.hpp"
#include "springlab/this_implementation.hpp"

const springlab::Implementation* springlab_dispatch =
    nullptr;  // declared extern "C" in dispatch.hpp

extern "C" const springlab::Implementation* springlab_submission_bind(
    const springlab::Implementation* host) {
  springlab_dispatch = host;
  return &springlab::implementation();
}
