// The front ends' option values, read from the text the user wrote: CLI11 would turn "nan" into a
// number that passes a range check, and an empty value into the default, without a word.
#pragma once

#include "springlab/parameters.hpp"

#include <initializer_list>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace springlab {

/// The number `text` gives for `option` (e.g. "--dt"), within `range`. Throws InvalidParameter
/// naming the option, the text as written and the range (e.g. `--dt = "nan": a number,
/// 0 < dt <= 10 s`) for an empty value, a value that is not a number, NaN, an infinity, a value
/// out of range, or a fraction where the range wants a whole number.
double option_number(std::string_view option, std::string_view text, const Range& range,
                     std::string_view unit = "");

/// The range of the scene parameter `key` (e.g. "step"), for an option that sets it.
Range parameter_range(std::string_view key);

/// An option that sets a scene parameter, e.g. --dt sets "step", and whether the user gave it.
struct OptionSetting {
  std::string_view option;  ///< e.g. "--dt"
  std::string_view key;     ///< the parameter it sets, e.g. "step"
  bool given = false;
};

/// Throws InvalidParameter when one of `assignments` (--set KEY=VALUE) names the parameter of an
/// option the user also gave ("--dt 0.03 --set step=0.001"), or one another assignment names
/// too: which of the two should win would be a guess, so neither does.
void refuse_double_settings(const std::vector<std::string>& assignments,
                            std::initializer_list<OptionSetting> options);

/// Throws InvalidParameter naming `option` when `path` is empty: an empty file name is a slip
/// (an unset shell variable), not a wish for no output.
void refuse_empty_path(std::string_view option, std::string_view path);

/// Flushes `out` and says why it could not be written ("standard output could not be written
/// (No space left on device)"), or "" when all of it was: a front end that lost its output says
/// so and exits 6 rather than 0.
std::string flush_failure(std::ostream& out);

/// x written with `digits` significant digits, or more (up to 17) until it reads differently from
/// `other`: "h = 0.00999999 s is below the limit 0.01 s", never "0.01 s ... 0.01 s", and a
/// growth of 1.000002 a step is not written "1".
std::string number_apart(double x, double other, int digits = 6);

/// How long `seconds` of wall time is, in words a person reads at a glance: "45 s",
/// "12 minutes", "3.4 hours", "2.3 days", "14 years".
std::string duration_in_words(double seconds);

}  // namespace springlab
