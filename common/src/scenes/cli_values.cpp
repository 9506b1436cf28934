#include "springlab/cli_values.hpp"

#include "springlab/errors.hpp"
#include "springlab/real_text.hpp"
#include "springlab/scene_text.hpp"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace springlab {

double option_number(std::string_view option, std::string_view text, const Range& range,
                     std::string_view unit) {
  const std::string name(option.substr(option.find_first_not_of('-')));
  const std::string shown = quoted_for_terminal(text);
  // "+2" is a number to a person; from_chars takes only "-" for a sign.
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  const RealText real = parse_real(digits);
  if (real.error == std::errc::result_out_of_range)
    throw InvalidParameter(std::string(option), shown,
                           "beyond the range of a double; allowed " + range.describe(name, unit));
  if (real.error != std::errc{})
    throw InvalidParameter(std::string(option), shown,
                           "not a number; allowed " + range.describe(name, unit));
  const double value = real.value;
  if (!range.contains(value))
    throw InvalidParameter(std::string(option), shown, "allowed " + range.describe(name, unit));
  return value;
}

Range parameter_range(std::string_view key) {
  const SceneParameters defaults;
  Range found;
  bool known = false;
  for_each_field(defaults, [&](const FieldInfo& info, const auto&) {
    if (info.key == key) found = info.range, known = true;
  });
  if (!known) throw std::logic_error("no scene parameter " + std::string(key));
  return found;
}

void refuse_double_settings(const std::vector<std::string>& assignments,
                            std::initializer_list<OptionSetting> options) {
  const auto key_of = [](const std::string& assignment) {
    return std::string_view(assignment).substr(0, assignment.find('='));
  };
  for (std::size_t i = 0; i < assignments.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (key_of(assignments[i]) == key_of(assignments[j]))
        throw InvalidParameter("--set", quoted_for_terminal(assignments[i]),
                               "once a parameter: " + printable(key_of(assignments[j])) +
                                   " is set already (" + quoted_for_terminal(assignments[j]) + ")");
  for (const std::string& assignment : assignments) {
    const std::string_view key = key_of(assignment);
    for (const OptionSetting& o : options)
      if (o.given && key == o.key)
        throw InvalidParameter("--set", quoted_for_terminal(assignment),
                               "not together with " + std::string(o.option) + ", which sets " +
                                   std::string(o.key) + " too: give one of the two");
  }
}

void refuse_empty_path(std::string_view option, std::string_view path) {
  if (path.empty())
    throw InvalidParameter(std::string(option), "\"\"",
                           "a file name (an empty one writes nothing)");
}

std::string flush_failure(std::ostream& out) {
  errno = 0;
  out.flush();
  if (out.good()) return "";
  const int reason = errno;  // read at once: what follows may change it
  return std::string("standard output could not be written") +
         (reason ? std::string(" (") + std::strerror(reason) + ")" : std::string());
}

std::string number_apart(double x, double other, int digits) {
  const auto text = [](double value, int precision) {
    char out[40];
    std::snprintf(out, sizeof out, "%.*g", precision, value);
    return std::string(out);
  };
  while (digits < 17 && x != other && text(x, digits) == text(other, digits))
    ++digits;
  return text(x, digits);
}

std::string duration_in_words(double seconds) {
  struct Unit {
    const char* name;
    double seconds;
  };
  // From the largest down: the first unit the time fills at least once.
  const Unit units[] = {
      {"years", 365.25 * 86400}, {"days", 86400}, {"hours", 3600}, {"minutes", 60}};
  char text[64];
  for (const Unit& unit : units)
    if (seconds >= unit.seconds) {
      std::snprintf(text, sizeof text, "%.2g %s", seconds / unit.seconds, unit.name);
      return text;
    }
  std::snprintf(text, sizeof text, "%.2g s", seconds);
  return text;
}

}  // namespace springlab
