// Every implementation build in one program: the reference and each "student's task N". Built
// with SPRINGLAB_REFERENCE_ONLY (the page in a browser without the student's code, viewer/web/),
// the reference alone.
#include "springlab/divergence.hpp"
#include "springlab/errors.hpp"
#include "springlab/implementation.hpp"

#include <string>

namespace springlab {
namespace reference {
const Implementation& implementation();
}
#ifndef SPRINGLAB_REFERENCE_ONLY
namespace student_task1 {
const Implementation& implementation();
}
namespace student_task2 {
const Implementation& implementation();
}
namespace student_task3 {
const Implementation& implementation();
}
namespace student_task4 {
const Implementation& implementation();
}
namespace student_task5 {
const Implementation& implementation();
}
#endif

const Implementation& reference_implementation() {
  return reference::implementation();
}

namespace {
// The diagnosis of a divergence runs the reference beside the code under test, where this
// program holds a reference that is the kit's (not a student's code standing in for it).
const bool reference_registered =
    (set_diagnosis_reference(reference_is_available() ? &reference::implementation() : nullptr),
     true);
}  // namespace

bool reference_is_available() {
#ifdef SPRINGLAB_NO_REFERENCE
  return false;
#else
  return true;
#endif
}

const Implementation& student_implementation(int task) {
#ifdef SPRINGLAB_REFERENCE_ONLY
  throw InvalidParameter("--impl student", "task " + std::to_string(task),
                         "a build with the student's code: ./lab web --impl student");
#else
  switch (task) {
    case 1:
      return student_task1::implementation();
    case 2:
      return student_task2::implementation();
    case 3:
      return student_task3::implementation();
    case 4:
      return student_task4::implementation();
    case 5:
      return student_task5::implementation();
  }
  throw InvalidParameter("task", std::to_string(task), "1, 2, 3, 4 or 5");
#endif
}

}  // namespace springlab
