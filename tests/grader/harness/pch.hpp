// Precompiled for every compilation of submission code (tests/grader/CMakeLists.txt): Eigen and
// the standard library only, never a kit header, so a submission's file still needs its own
// includes.
#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>
