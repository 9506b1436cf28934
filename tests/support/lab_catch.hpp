// Catch2 for the kit's tests, whichever major version the system has: Catch2 2.13 (Debian 12,
// Ubuntu 22.04) is one header; Catch2 3 (Debian 13, Ubuntu 24.04 and later, Homebrew, vcpkg) is a
// compiled library with a header per part and a few names moved. The tests use only the names
// below (lab_catch::Contains for "the text contains", not Catch2 3's range matcher of that name),
// so one source compiles against both. CMake defines SPRINGLAB_CATCH2_MAJOR (CMakeLists.txt).
#pragma once

#ifndef SPRINGLAB_CATCH2_MAJOR
#error "SPRINGLAB_CATCH2_MAJOR is set by the kit's CMakeLists.txt: link springlab_catch2"
#endif

#if SPRINGLAB_CATCH2_MAJOR >= 3
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>
#include <catch2/generators/catch_generators_adapters.hpp>
#include <catch2/generators/catch_generators_range.hpp>
#include <catch2/matchers/catch_matchers.hpp>
#include <catch2/matchers/catch_matchers_floating_point.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <limits>
#include <sstream>
#include <string>

namespace lab_catch {
using Catch::Approx;
using Catch::Matchers::EndsWith;
using Catch::Matchers::MatcherBase;
using Catch::Matchers::StartsWith;
using Catch::Matchers::WithinAbs;
/// The text contains `part` (Catch2 3 calls this ContainsSubstring).
inline auto Contains(const std::string& part,
                     Catch::CaseSensitive sensitivity = Catch::CaseSensitive::Yes) {
  return Catch::Matchers::ContainsSubstring(part, sensitivity);
}

/// Catch2 3's WithinRel, described in Catch2 2's words: Catch2 3 writes the target with all the
/// digits doubles are printed with (-0.324427186079791), Catch2 2 as a stream does (-0.324427),
/// and the grader's feedback must read the same with either.
class WithinRelMatcher : public MatcherBase<double> {
 public:
  WithinRelMatcher(double target, double epsilon)
      : within_(target, epsilon), target_(target), epsilon_(epsilon) {}
  bool match(const double& value) const override { return within_.match(value); }
  std::string describe() const override {
    std::ostringstream out;
    out << "and " << target_ << " are within " << epsilon_ * 100. << "% of each other";
    return out.str();
  }

 private:
  Catch::Matchers::WithinRelMatcher within_;
  double target_, epsilon_;
};
inline WithinRelMatcher WithinRel(double target, double epsilon) {
  return {target, epsilon};
}
inline WithinRelMatcher WithinRel(double target) {
  return {target, std::numeric_limits<double>::epsilon() * 100};
}
}  // namespace lab_catch
#else
#include <catch2/catch.hpp>

namespace lab_catch {
using Catch::MatcherBase;
using Catch::Detail::Approx;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::StartsWith;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
}  // namespace lab_catch
#endif
