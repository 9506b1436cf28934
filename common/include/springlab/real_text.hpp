// A real number read from a whole text ("0.01", "-2e3", "inf", "nan"): the form std::from_chars
// accepts (no '+', no spaces, nothing after the number). libc++ before version 20 (macOS's
// toolchain, issue 36) has no std::from_chars for double; there the same form is checked by hand
// and converted by strtod in the "C" locale, which gives the correctly rounded double as
// from_chars does.
#pragma once

#include <string>
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

/// x as the shortest text that reads back exactly, as std::to_chars(first, last, x) writes it:
/// "0.01", "1e-06", "100000", "-inf", "nan". libc++ before version 14 (Emscripten 3.1.6's, for
/// the page in a browser, viewer/web/) has no std::to_chars for double; there the text is found
/// with snprintf: the fewest significant digits that read back exactly, written fixed or
/// scientific, whichever is shorter (fixed on a tie), as to_chars chooses; a whole number written
/// fixed has its exact digits, as to_chars writes them.
std::string shortest_text(double x);

/// The same, never through std::to_chars, so that a test compares the two.
std::string shortest_text_portable(double x);

}  // namespace springlab
