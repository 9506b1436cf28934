// The checks a scene file's text passes before toml++ reads it. toml++ 3.3.0 (Debian 12's)
// recurses once per level of nesting (a file nested 300,000 levels deep overflows its stack) and
// has undefined behaviour on some malformed input: a non-ASCII character outside strings and
// comments reaches an "unreachable" point, and a table header opening with a character that
// cannot start a key ("[#", "[=") or an array element starting with "}" ("[1, }") breaks an
// assumption. Such text is refused here first.
#pragma once

#include <string>
#include <string_view>

namespace springlab {

/// How deep a scene file may nest tables, dotted keys, inline tables and arrays. The kit's
/// deepest keys have 3 levels (wind.direction.x); the rest is margin.
inline constexpr int max_scene_nesting = 8;

/// Throws InvalidParameter naming `path`, the line and what is wrong for text that is not UTF-8,
/// has control characters (other than tab and line ends) or non-ASCII characters outside strings
/// and comments, a table header that does not start with a key, or deeper nesting than
/// max_scene_nesting. Reads the text once, with no recursion.
void check_scene_text(std::string_view text, const std::string& path);

/// `text` with control characters written as \xNN, so that a terminal shows them instead of
/// obeying them (ESC starts a terminal command).
std::string printable(std::string_view text);

/// printable(text), but line ends and tabs kept: for a whole message of several lines.
std::string printable_lines(std::string_view text);

/// printable(text) in double quotes; a text longer than 120 bytes as its first 100 and its
/// length, e.g. "0.000000...\" (100000 bytes): a pasted file is not echoed whole.
std::string quoted_for_terminal(std::string_view text);

/// Whether `text` is valid UTF-8 (no overlong forms, surrogates or values above U+10FFFF).
bool is_utf8(std::string_view text);

/// Whether `text` (UTF-8) has a control character: C0, DEL or C1 (U+0080 to U+009F).
bool has_control_character(std::string_view text);

}  // namespace springlab
