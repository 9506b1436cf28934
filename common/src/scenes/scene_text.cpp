#include "springlab/scene_text.hpp"

#include "springlab/errors.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <vector>

namespace springlab {
namespace {

[[noreturn]] void refuse(const std::string& path, int line, const std::string& what,
                         const std::string& allowed) {
  throw InvalidParameter(path + ":" + std::to_string(line), "(" + what + ")", allowed);
}

std::string code_point_name(char32_t c) {
  char text[16];
  std::snprintf(text, sizeof text, "U+%04X", unsigned(c));
  return text;
}

bool is_control(char32_t c) {
  return c < 0x20 || c == 0x7F || (c >= 0x80 && c <= 0x9F);
}

unsigned char byte_at(std::string_view text, std::size_t at) {
  return at < text.size() ? static_cast<unsigned char>(text[at]) : 0;
}

// The code point at text[at] and its length in bytes; length 0 if the bytes are not UTF-8
// (overlong forms, surrogates and values above U+10FFFF included).
std::size_t decode(std::string_view text, std::size_t at, char32_t& c) {
  const unsigned char lead = byte_at(text, at);
  if (lead < 0x80) return c = lead, 1;
  std::size_t length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 0;
  if (length == 0 || lead > 0xF4) return 0;
  c = lead & (0x7F >> length);
  for (std::size_t i = 1; i < length; ++i) {
    const unsigned char next = byte_at(text, at + i);
    if ((next & 0xC0) != 0x80) return 0;
    c = (c << 6) | (next & 0x3F);
  }
  const char32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (c < smallest[length] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return 0;
  return length;
}

// Every character: UTF-8, and no control characters but tab and line ends.
void check_characters(std::string_view text, const std::string& path) {
  int line = 1;
  for (std::size_t at = 0; at < text.size();) {
    char32_t c = 0;
    const std::size_t length = decode(text, at, c);
    if (length == 0)
      refuse(path, line, "bytes that are not UTF-8", "a scene file is text in UTF-8");
    // A line ends in \n or \r\n; toml++ 3.3.0 mishandles a lone \r inside a value.
    const bool line_end = c == '\n' || (c == '\r' && byte_at(text, at + 1) == '\n');
    if (is_control(c) && c != '\t' && !line_end)
      refuse(path, line, "the control character " + code_point_name(c),
             "no control characters; tabs and line ends only");
    line += c == '\n';
    at += length;
  }
}

// Reads the text as TOML's grammar nests it: table headers, dotted keys, inline tables and
// arrays, skipping strings and comments, with an explicit stack instead of recursion.
class NestingScan {
 public:
  NestingScan(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  void run() {
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == '\n') {
        ++line_, ++at_;
        end_of_line();
      } else if (c == '#') {
        while (at_ < text_.size() && text_[at_] != '\n')
          ++at_;
      } else if ((c == '"' || c == '\'') && at_start_) {
        skip_string(c);
        key_started_ = true, at_start_ = false;
      } else if (static_cast<unsigned char>(c) >= 0x80) {
        refuse_non_ascii();
      } else {
        ++at_;
        key_position_ ? key_character(c) : value_character(c);
      }
    }
    if (over_line_) refuse_depth();
  }

 private:
  enum class Kind { table, array };
  struct Open {
    Kind kind;
    int outer_depth;  // the depth of the container it is in
  };

  void end_of_line() {
    in_bare_ = false;
    if (!open_.empty()) return;  // an array goes on over several lines
    if (over_line_) refuse_depth();
    start_key();
  }

  void start_key() { key_position_ = at_start_ = true, key_started_ = false, key_segments_ = 1; }

  void key_character(char c) {
    if (c == ' ' || c == '\t' || c == '\r') return;
    if (c == '[' && open_.empty() && !key_started_) return table_header();
    at_start_ = c == '.' || c == '=';
    if (c == '.') return note(container_ + ++key_segments_);
    if (c == '}') return close();
    if (c == '=') {
      value_depth_ = container_ + key_segments_;
      key_position_ = false;
      return note(value_depth_);
    }
    key_started_ = true;
  }

  void value_character(char c) {
    if (c == ' ' || c == '\t' || c == '\r') {
      in_bare_ = false;
      return;
    }
    // A bare value (1e5, true, a date, or garbage) runs to a blank, ',', ']' or '}' as toml++
    // reads it: a '[', '{' or quote inside it opens nothing.
    if (in_bare_ && c != ',' && c != ']' && c != '}') return;
    in_bare_ = false;
    at_start_ = c == '[' || (c == ',' && !open_.empty());
    if (c == '{' || c == '[') {
      open_.push_back({c == '{' ? Kind::table : Kind::array, container_});
      container_ = value_depth_;
      if (c == '{') return start_key();
      value_depth_ = container_ + 1;
      return note(value_depth_);
    }
    // toml++ 3.3.0 assumes an array's element never starts with '}' ("[1, }").
    if (c == '}' && !open_.empty() && open_.back().kind == Kind::array)
      refuse(path_, line_, "a '}' inside an array", "an array closed with ']', e.g. [1, 2]");
    if (c == '}' || c == ']') return close();
    if (c == ',' && !open_.empty()) {
      if (open_.back().kind == Kind::table) return start_key();
      value_depth_ = container_ + 1;
    }
    in_bare_ = c != ',';
  }

  void close() {
    if (!open_.empty()) container_ = open_.back().outer_depth, open_.pop_back();
    key_position_ = false;
  }

  // "[a.b]" or "[[a.b]]": its depth is its number of keys. toml++ 3.3.0 assumes that a
  // header's first character can start a key, so anything else is refused here.
  void table_header() {
    if (at_ < text_.size() && text_[at_] == '[') ++at_;
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t'))
      ++at_;
    const char first = at_ < text_.size() ? text_[at_] : '\n';
    const bool bare = std::isalnum(static_cast<unsigned char>(first)) || first == '_' ||
                      first == '-' || first == '"' || first == '\'';
    if (!bare)
      refuse(path_, line_, "a table header that does not start with a name",
             "a table's name in brackets, e.g. [structural] or [wind.direction]");
    int keys = 1;
    bool key_starts = true;  // a quote opens a string only where a key begins
    while (at_ < text_.size() && text_[at_] != ']' && text_[at_] != '\n' && text_[at_] != '#') {
      const char c = text_[at_];
      if ((c == '"' || c == '\'') && key_starts) {
        skip_string(c);
        key_starts = false;
        continue;
      }
      if (static_cast<unsigned char>(c) >= 0x80) refuse_non_ascii();
      keys += c == '.';
      if (c != ' ' && c != '\t') key_starts = c == '.';
      ++at_;
    }
    container_ = keys;
    note(keys);
    key_started_ = true;  // what follows on the line is toml++'s to judge
  }

  // A string or quoted key: '...', "..." (with escapes), '''...''' or """...""".
  void skip_string(char quote) {
    const bool multiline = byte_at(text_, at_ + 1) == quote && byte_at(text_, at_ + 2) == quote;
    at_ += multiline ? 3 : 1;
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == '\n') {
        if (!multiline) return;  // unterminated: toml++ says so
        ++line_;
      }
      // toml++ 3.3.0 asks whether the character after a backslash (and after the blanks and
      // line ends a line-ending backslash skips) is whitespace, which is undefined for most
      // non-ASCII characters; no TOML escape is one anyway.
      if (c == '\\' && quote == '"' && byte_at(text_, after_blanks(at_ + 1)) >= 0x80)
        refuse(path_, line_, "a backslash before a non-ASCII character",
               "escapes such as \\n, \\t, \\\" or \\u00E9 in a \"string\"");
      if (c == '\\' && quote == '"' && byte_at(text_, at_ + 1) != '\n') {
        at_ += 2;
        continue;
      }
      if (c == quote &&
          (!multiline || (byte_at(text_, at_ + 1) == quote && byte_at(text_, at_ + 2) == quote))) {
        at_ += multiline ? 3 : 1;
        while (multiline && at_ < text_.size() && text_[at_] == quote)
          ++at_;  // """a"""""
        return;
      }
      ++at_;
    }
  }

  std::size_t after_blanks(std::size_t at) const {
    while (at < text_.size() &&
           (text_[at] == ' ' || text_[at] == '\t' || text_[at] == '\r' || text_[at] == '\n'))
      ++at;
    return at;
  }

  [[noreturn]] void refuse_non_ascii() {
    char32_t c = 0;
    decode(text_, at_, c);
    refuse(path_, line_, "the character " + code_point_name(c) + " outside quotes",
           "keys and values in ASCII; other characters only inside \"strings\" and # comments");
  }

  // Remembers the first line nested too deeply and, until its statement ends, how deep it goes.
  void note(int depth) {
    if (depth > max_scene_nesting && !over_line_) over_line_ = line_;
    if (over_line_) deepest_ = std::max(deepest_, depth);
  }

  [[noreturn]] void refuse_depth() {
    refuse(path_, over_line_, "nested " + std::to_string(deepest_) + " levels deep",
           "at most " + std::to_string(max_scene_nesting) +
               " levels of tables, dotted keys, inline tables and arrays (the kit's deepest "
               "keys, such as wind.direction.x, have 3)");
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t at_ = 0;
  int line_ = 1;
  int container_ = 0;    // depth of the table or array whose keys or elements come next
  int value_depth_ = 0;  // depth of the value being read
  int key_segments_ = 1;
  bool key_position_ = true;
  bool key_started_ = false;
  bool at_start_ = true;  // where a key or a value begins: only there a quote opens a string
  bool in_bare_ = false;  // inside a bare value
  std::vector<Open> open_;
  int over_line_ = 0;
  int deepest_ = 0;
};

}  // namespace

void check_scene_text(std::string_view text, const std::string& path) {
  check_characters(text, path);
  NestingScan(text, path).run();
}

bool is_utf8(std::string_view text) {
  for (std::size_t at = 0; at < text.size();) {
    char32_t c = 0;
    const std::size_t length = decode(text, at, c);
    if (length == 0) return false;
    at += length;
  }
  return true;
}

bool has_control_character(std::string_view text) {
  for (std::size_t at = 0; at < text.size(); ++at) {
    const unsigned char b = static_cast<unsigned char>(text[at]);
    if (b < 0x20 || b == 0x7F ||
        (b == 0xC2 && byte_at(text, at + 1) >= 0x80 && byte_at(text, at + 1) <= 0x9F))
      return true;
  }
  return false;
}

// Characters that reorder the text around them on a terminal (Unicode's bidirectional
// controls): shown, never obeyed, as control characters are.
namespace {
bool is_bidi_control(char32_t c) {
  return c == 0x061C || c == 0x200E || c == 0x200F || (c >= 0x202A && c <= 0x202E) ||
         (c >= 0x2066 && c <= 0x2069);
}
}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  char code[16];
  for (std::size_t at = 0; at < text.size();) {
    char32_t c = 0;
    const std::size_t length = decode(text, at, c);
    if (length == 0) {  // not UTF-8: a lone byte such as 0x9B, the 8-bit CSI of some terminals
      std::snprintf(code, sizeof code, "\\x%02X", unsigned(byte_at(text, at)));
      out += code;
      ++at;
      continue;
    }
    if (is_control(c) && c < 0x80)
      std::snprintf(code, sizeof code, "\\x%02X", unsigned(c));
    else if (is_control(c))
      std::snprintf(code, sizeof code, "\\xC2\\x%02X", unsigned(c));
    else if (is_bidi_control(c))
      std::snprintf(code, sizeof code, "\\u%04X", unsigned(c));
    else
      code[0] = '\0';
    out += code[0] ? std::string(code) : std::string(text.substr(at, length));
    at += length;
  }
  return out;
}

std::string printable_lines(std::string_view text) {
  std::string out;
  std::size_t start = 0;
  for (std::size_t at = 0; at <= text.size(); ++at)
    if (at == text.size() || text[at] == '\n' || text[at] == '\t') {
      out += printable(text.substr(start, at - start));
      if (at < text.size()) out += text[at];
      start = at + 1;
    }
  return out;
}

std::string quoted_for_terminal(std::string_view text) {
  constexpr std::size_t shown = 100, longest = 120;  // bytes
  // Appended piece by piece: GCC 12 at -O3 warns falsely about "\"" + std::string (bug 105329).
  std::string quoted = "\"";
  if (text.size() <= longest) return quoted.append(printable(text)).append("\"");
  std::size_t cut = shown;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)
    --cut;  // not inside a character
  return quoted.append(printable(text.substr(0, cut)))
      .append("...\" (")
      .append(std::to_string(text.size()))
      .append(" bytes)");
}

}  // namespace springlab
