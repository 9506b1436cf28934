// Compiled into every submission library: the library's own pointer to the table in use, the
// function the worker calls to run the library's initialisers, and the one that points that
// pointer at the worker's table and returns the library's own task functions.
#include "dispatch.hpp"
#include "springlab/this_implementation.hpp"

const springlab::Implementation* springlab_dispatch =
    nullptr;  // declared extern "C" in dispatch.hpp

extern "C" const springlab::Implementation* springlab_submission_bind(
    const springlab::Implementation* host) {
  springlab_dispatch = host;
  return &springlab::implementation();
}

// The library is linked with deferred_init.ld, which moves every initialiser (a global's
// constructor, a static object's set-up) out of reach of the dynamic loader, between these two
// symbols: loading the library runs no submission code, and the worker runs them here once it
// may no longer make memory executable (harness/main.cpp).
using Initialiser = void (*)();
extern "C" Initialiser springlab_init_start[] __attribute__((visibility("hidden")));
extern "C" Initialiser springlab_init_end[] __attribute__((visibility("hidden")));

extern "C" void springlab_submission_init() {
  for (Initialiser* f = springlab_init_start; f != springlab_init_end; ++f)
    (*f)();
}
