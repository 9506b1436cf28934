// The front ends' option values, read from the text the user wrote: CLI11 would turn "nan" into a
// number that passes a range check, and an empty value into the default, without a word.
#pragma once

#include "springlab/parameters.hpp"

#include <string>
#include <string_view>

namespace springlab {

/// The number `text` gives for `option` (e.g. "--dt"), within `range`. Throws InvalidParameter
/// naming the option, the text as written and the range (e.g. `--dt = "nan": a number,
/// 0 < dt <= 10 s`) for an empty value, a value that is not a number, NaN, an infinity, a value
/// out of range, or a fraction where the range wants a whole number.
double option_number(std::string_view option, std::string_view text, const Range& range,
                     std::string_view unit = "");

/// The range of the scene parameter `key` (e.g. "step"), for an option that sets it.
Range parameter_range(std::string_view key);

/// How long `seconds` of wall time is, in words a person reads at a glance: "45 s",
/// "12 minutes", "3.4 hours", "2.3 days", "14 years".
std::string duration_in_words(double seconds);

}  // namespace springlab
