// The parts of Catch2 the harness uses beyond the tests' own (its reporter, session and test
// registry), whichever major version the system has; the one place where the harness tells them
// apart. Catch2 2 declares them in its single header when asked to (and compiles its whole
// implementation where CATCH_CONFIG_RUNNER is defined first: catch_runner.cpp); Catch2 3 has a
// header per part and drops the reporter base's template parameter.
#pragma once

#if SPRINGLAB_CATCH2_MAJOR >= 3
#include "lab_catch.hpp"

#include <catch2/catch_config.hpp>
#include <catch2/catch_session.hpp>
#include <catch2/catch_test_case_info.hpp>
#include <catch2/catch_translate_exception.hpp>
#include <catch2/internal/catch_test_case_registry_impl.hpp>
#include <catch2/reporters/catch_reporter_registrars.hpp>
#include <catch2/reporters/catch_reporter_streaming_base.hpp>
#else
#define CATCH_CONFIG_EXTERNAL_INTERFACES  // the reporter base classes
#include "lab_catch.hpp"
#endif

#include <string>

namespace springlab::grading::catch_internals {

#if SPRINGLAB_CATCH2_MAJOR >= 3
template <typename Reporter>
using ReporterBase = Catch::StreamingReporterBase;
using TestCase = Catch::TestCaseHandle;
/// What a reporter's assertionEnded returns: nothing in Catch2 3, a bool Catch2 2 ignores.
using AssertionEnded = void;

inline std::string tag_name(const Catch::Tag& tag) {
  return std::string(tag.original);
}
#else
template <typename Reporter>
using ReporterBase = Catch::StreamingReporterBase<Reporter>;
using TestCase = Catch::TestCase;
using AssertionEnded = bool;

inline std::string tag_name(const std::string& tag) {
  return tag;
}
#endif

}  // namespace springlab::grading::catch_internals
