#include "springlab/real_text.hpp"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace springlab {
namespace {

bool digit(char c) {
  return c >= '0' && c <= '9';
}

bool same_letters(std::string_view text, std::string_view lower) {
  if (text.size() != lower.size()) return false;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[i])) != lower[i]) return false;
  return true;
}

// from_chars's general form: digits with at most one '.', at least one digit, then an optional
// exponent e[+-]digits; or inf, infinity, nan, nan(letters, digits, _), in any case.
bool real_form(std::string_view t) {
  if (same_letters(t, "inf") || same_letters(t, "infinity") || same_letters(t, "nan")) return true;
  if (t.size() > 4 && same_letters(t.substr(0, 4), "nan(") && t.back() == ')') {
    for (const char c : t.substr(4, t.size() - 5))
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
    return true;
  }
  std::size_t i = 0, digits = 0;
  for (; i < t.size() && digit(t[i]); ++i)
    ++digits;
  if (i < t.size() && t[i] == '.')
    for (++i; i < t.size() && digit(t[i]); ++i)
      ++digits;
  if (digits == 0) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < t.size() && (t[j] == '+' || t[j] == '-')) ++j;
    const std::size_t exponent_start = j;
    while (j < t.size() && digit(t[j]))
      ++j;
    if (j == exponent_start) return false;
    i = j;
  }
  return i == t.size();
}

}  // namespace

RealText parse_real_portable(std::string_view text) {
  std::string_view unsigned_part = text;
  if (!unsigned_part.empty() && unsigned_part.front() == '-') unsigned_part.remove_prefix(1);
  if (!real_form(unsigned_part)) return {};
  const std::string copy(text);
  // strtod reads the decimal point of the C library's locale; the kit never changes it from "C",
  // and a library that did would be caught here rather than misread "0.5".
  const char* point = std::localeconv()->decimal_point;
  if (point == nullptr || std::string_view(point) != ".") return {};
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size()) return {};
  if (errno == ERANGE && (std::isinf(value) || value == 0.0))
    return {value, std::errc::result_out_of_range};
  return {value, std::errc{}};
}

RealText parse_real(std::string_view text) {
#if defined(__cpp_lib_to_chars)  // libstdc++ 11 and later, MSVC; libc++ from version 20
  RealText out;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out.value);
  if (text.empty() || end != text.data() + text.size()) return {};
  out.error = error;
  return out;
#else
  return parse_real_portable(text);
#endif
}

std::string shortest_text_portable(double x) {
  if (std::isnan(x)) return std::signbit(x) ? "-nan" : "nan";
  if (std::isinf(x)) return x < 0 ? "-inf" : "inf";
  if (x == 0) return std::signbit(x) ? "-0" : "0";
  char text[40];
  int digits = 1;
  for (; digits < 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*e", digits - 1, x);
    if (std::strtod(text, nullptr) == x) break;
  }
  std::snprintf(text, sizeof text, "%.*e", digits - 1, x);
  const std::string scientific = text;  // "-1.25e+02": a sign, the digits, the exponent
  const std::size_t e = scientific.find('e');
  const int exponent = std::atoi(scientific.c_str() + e + 1);
  std::string significant;
  for (const char c : scientific.substr(0, e))
    if (digit(c)) significant += c;
  const int count = int(significant.size());
  std::string fixed = x < 0 ? "-" : "";
  if (exponent < 0)
    fixed += "0." + std::string(std::size_t(-exponent - 1), '0') + significant;
  else if (exponent + 1 >= count && exponent < 24) {
    // A whole number: to_chars writes its exact digits, as "%.0f" does.
    std::snprintf(text, sizeof text, "%.0f", x);
    fixed = text;
  } else if (exponent + 1 >= count) {
    // Longer than the scientific text in any case: its digits and zeros.
    fixed += significant + std::string(std::size_t(exponent + 1 - count), '0');
  } else
    fixed += significant.substr(0, std::size_t(exponent + 1)) + "." +
             significant.substr(std::size_t(exponent + 1));
  return fixed.size() <= scientific.size() ? fixed : scientific;
}

std::string shortest_text(double x) {
#if defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 14000
  return shortest_text_portable(x);
#else
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof text, x);
  return error == std::errc{} ? std::string(text, end) : std::string("?");
#endif
}

}  // namespace springlab
