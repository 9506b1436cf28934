// How the task headers declare the functions students write.
//
// The kit builds every task file more than once: from solutions/ as the reference, and, for each
// task N, as "the student's task N with the reference for every other task" (the build that the
// task N tests grade and that the runner shows as --impl student). Each build is compiled into
// its own inline namespace, named by SPRINGLAB_IMPL, so one program can hold all of them side by
// side. Students never write the namespace: they define functions with qualified names, e.g.
//   Vec2 springlab::spring_force(...) { ... }
// which also turns a mistyped signature into a compile error instead of a silent new function.
#pragma once

#ifndef SPRINGLAB_IMPL
#error "SPRINGLAB_IMPL is not set: only the kit's implementation builds include the task headers"
#endif

#define SPRINGLAB_TASK_API_BEGIN \
  namespace springlab {          \
  inline namespace SPRINGLAB_IMPL {
#define SPRINGLAB_TASK_API_END \
  }                            \
  }
