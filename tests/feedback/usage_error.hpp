// Bad usage of the kit's graders (springlab-grade, springlab-check): a wrong option, a points file
// that names no test. The program exits with status 2 and this message.
#pragma once

#include <stdexcept>

namespace springlab::grader {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace springlab::grader
