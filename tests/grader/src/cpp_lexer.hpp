// A lexer of C++ source, enough to find identifiers, directives and punctuators outside comments
// and literals (raw strings, digit separators and line splices included), with the line each
// starts on: for the source policy (policy.hpp) and the release's search for solution code.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace springlab::grader {

struct Token {
  enum Kind { identifier, literal, punctuator, directive } kind = punctuator;
  std::string text;        ///< as written (a directive: its name, "include")
  int line = 0;            ///< 1-based, of the physical line it starts on
  std::size_t offset = 0;  ///< where it starts in the text after line splices are joined
};

class Lexer {
 public:
  explicit Lexer(const std::string& source);
  /// The next token, false at the end.
  bool next(Token& t);
  /// The rest of the current line, as written (a directive's operands).
  std::string rest_of_line();

 private:
  std::string text_;       // the source after translation phases 1-2 (line splices joined)
  std::vector<int> line_;  // the physical line of every character of text_
  std::size_t i_ = 0;
  bool line_start_ = true;

  void skip_blanks();
  std::size_t literal_start() const;
  void read_literal();
};

/// Every token of `source`.
std::vector<Token> tokens(const std::string& source);

}  // namespace springlab::grader
