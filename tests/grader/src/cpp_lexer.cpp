#include "cpp_lexer.hpp"

#include <cctype>
#include <cstring>
#include <string_view>

namespace springlab::grader {
namespace {

bool is_identifier_start(unsigned char c) {
  return std::isalpha(c) || c == '_' || c == '$' || c >= 0x80;
}

bool is_identifier_char(unsigned char c) {
  return is_identifier_start(c) || std::isdigit(c);
}

// A blank within a line as GCC reads one (a carriage return only ever ends a line here: the
// source policy refuses one that does not).
bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

}  // namespace

// Translation phases 1-2: a backslash at the end of a line joins it to the next (GCC allows
// blanks between the two, form feed and vertical tab included); each character keeps its
// physical line, for messages.
Lexer::Lexer(const std::string& source) {
  text_.reserve(source.size());
  line_.reserve(source.size());
  int line = 1;
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (source[i] == '\\') {
      std::size_t k = i + 1;
      while (k < source.size() && is_blank(source[k]))
        ++k;
      if (k < source.size() && source[k] == '\n') {
        i = k;
        ++line;
        continue;
      }
    }
    text_.push_back(source[i]);
    line_.push_back(line);
    if (source[i] == '\n') ++line;
  }
}

bool Lexer::next(Token& t) {
  const std::string& s = text_;
  while (i_ < s.size()) {
    const char c = s[i_];
    if (c == '\n') {
      line_start_ = true;
      ++i_;
    } else if (is_blank(c)) {
      ++i_;
    } else if (s.compare(i_, 2, "//") == 0) {
      while (i_ < s.size() && s[i_] != '\n')
        ++i_;
    } else if (s.compare(i_, 2, "/*") == 0) {
      const auto end = s.find("*/", i_ + 2);
      i_ = end == std::string::npos ? s.size() : end + 2;
    } else {
      break;
    }
  }
  if (i_ >= s.size()) return false;
  t.line = line_[i_];
  t.offset = i_;
  const bool at_start = line_start_;
  line_start_ = false;
  const char c = s[i_];
  if (at_start && (c == '#' || s.compare(i_, 2, "%:") == 0)) {
    i_ += c == '#' ? 1 : 2;
    t.kind = Token::directive;
    skip_blanks();
    const std::size_t from = i_;
    while (i_ < s.size() && is_identifier_char(static_cast<unsigned char>(s[i_])))
      ++i_;
    t.text = s.substr(from, i_ - from);
    return true;
  }
  if (const std::size_t quote = literal_start(); quote != std::string::npos) {
    t.kind = Token::literal;
    const std::size_t from = i_;
    i_ = quote;
    read_literal();
    t.text = s.substr(from, i_ - from);
    return true;
  }
  if (std::isdigit(static_cast<unsigned char>(c)) ||
      (c == '.' && i_ + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i_ + 1])))) {
    t.kind = Token::literal;  // a pp-number: digit separators and exponents' signs included
    const std::size_t from = i_++;
    while (i_ < s.size()) {
      const auto d = static_cast<unsigned char>(s[i_]);
      if ((d == '+' || d == '-') && std::string_view("eEpP").find(s[i_ - 1]) != std::string::npos)
        ++i_;
      else if (d == '\'' && i_ + 1 < s.size() &&
               is_identifier_char(static_cast<unsigned char>(s[i_ + 1])))
        i_ += 2;
      else if (is_identifier_char(d) || d == '.')
        ++i_;
      else
        break;
    }
    t.text = s.substr(from, i_ - from);
    return true;
  }
  if (is_identifier_start(static_cast<unsigned char>(c))) {
    t.kind = Token::identifier;
    const std::size_t from = i_;
    while (i_ < s.size() && is_identifier_char(static_cast<unsigned char>(s[i_])))
      ++i_;
    t.text = s.substr(from, i_ - from);
    return true;
  }
  t.kind = Token::punctuator;
  t.text = std::string(1, c);
  ++i_;
  return true;
}

std::string Lexer::rest_of_line() {
  const auto end = text_.find('\n', i_);
  const std::size_t stop = end == std::string::npos ? text_.size() : end;
  std::string rest = text_.substr(i_, stop - i_);
  i_ = stop;
  return rest;
}

// Between '#' and a directive's name: blanks as GCC reads them (a form feed there is one too).
void Lexer::skip_blanks() {
  while (i_ < text_.size()) {
    if (is_blank(text_[i_])) {
      ++i_;
    } else if (text_.compare(i_, 2, "/*") == 0) {
      const auto end = text_.find("*/", i_ + 2);
      i_ = end == std::string::npos ? text_.size() : end + 2;
    } else {
      break;
    }
  }
}

// Where the quote of a string or character literal starting here is (after a prefix such as
// u8, L or R), or npos.
std::size_t Lexer::literal_start() const {
  for (const char* prefix : {"u8R", "uR", "UR", "LR", "R", "u8", "u", "U", "L", ""})
    if (text_.compare(i_, std::strlen(prefix), prefix) == 0) {
      const std::size_t k = i_ + std::strlen(prefix);
      if (k < text_.size() &&
          (text_[k] == '"' || (text_[k] == '\'' && std::strchr(prefix, 'R') == nullptr)))
        return k;
    }
  return std::string::npos;
}

void Lexer::read_literal() {
  const char quote = text_[i_];
  const bool raw = quote == '"' && i_ > 0 && text_[i_ - 1] == 'R';
  if (raw) {
    const auto open = text_.find('(', i_);
    const std::string end =
        ")" + text_.substr(i_ + 1, open == std::string::npos ? 0 : open - i_ - 1) + "\"";
    const auto close = open == std::string::npos ? open : text_.find(end, open);
    i_ = close == std::string::npos ? text_.size() : close + end.size();
    return;
  }
  for (++i_; i_ < text_.size() && text_[i_] != quote && text_[i_] != '\n'; ++i_)
    if (text_[i_] == '\\') ++i_;
  if (i_ < text_.size() && text_[i_] == quote) ++i_;
}

std::vector<Token> tokens(const std::string& source) {
  std::vector<Token> all;
  Lexer lexer(source);
  for (Token t; lexer.next(t);)
    all.push_back(t);
  return all;
}

}  // namespace springlab::grader
