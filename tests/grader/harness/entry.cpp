// Compiled into every submission library the grader links (tests/grader/src/build.cpp): the one
// symbol the harness looks up after loading it, the library's table of task functions.
#include "springlab/this_implementation.hpp"

extern "C" const springlab::Implementation* springlab_submission_implementation() {
  return &springlab::implementation();
}
