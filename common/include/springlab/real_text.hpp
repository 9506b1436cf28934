// A real number read from a whole text ("0.01", "-2e3", "inf", "nan"): the form std::from_chars
// accepts (no '+', no spaces, nothing after the number). libc++ before version 20 (macOS's
// toolchain, issue 36) has no std::from_chars for double; there the same form is checked by hand
// and converted by strtod in the "C" locale, which gives the correctly rounded double as
// from_chars does.
#pragma once

#include <string_view>
#include <system_error>

namespace springlab {

/// The text as a double: error is std::errc{} when the whole text is a number,
/// invalid_argument when it is not, result_out_of_range when it is beyond a double's range.
struct RealText {
  double value = 0.0;
  std::errc error = std::errc::invalid_argument;
};
RealText parse_real(std::string_view text);

/// The same, never through std::from_chars: what parse_real does where the standard library has
/// no from_chars for double, callable everywhere so that a test compares the two.
RealText parse_real_portable(std::string_view text);

}  // namespace springlab
