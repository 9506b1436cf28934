#include "task_results.hpp"

#include <algorithm>

namespace springlab::grader {

double TaskResult::points() const {
  double sum = 0.0;
  for (const TestResult& t : tests)
    sum += t.passed ? t.test->points : 0.0;
  return sum;
}

double TaskResult::max_points() const {
  double sum = 0.0;
  for (const TestResult& t : tests)
    sum += t.test->points;
  return sum;
}

int TaskResult::passed() const {
  return int(
      std::count_if(tests.begin(), tests.end(), [](const TestResult& t) { return t.passed; }));
}

}  // namespace springlab::grader
