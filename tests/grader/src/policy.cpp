#include "policy.hpp"

#include "cpp_lexer.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>

namespace springlab::grader {
namespace {

constexpr std::array standard_headers = {
    // C++20 ([headers], table 21-24)
    "algorithm", "any", "array", "atomic", "barrier", "bit", "bitset", "charconv", "chrono",
    "codecvt", "compare", "complex", "concepts", "condition_variable", "coroutine", "deque",
    "exception", "execution", "filesystem", "format", "forward_list", "fstream", "functional",
    "future", "initializer_list", "iomanip", "ios", "iosfwd", "iostream", "istream", "iterator",
    "latch", "limits", "list", "locale", "map", "memory", "memory_resource", "mutex", "new",
    "numbers", "numeric", "optional", "ostream", "queue", "random", "ranges", "ratio", "regex",
    "scoped_allocator", "semaphore", "set", "shared_mutex", "source_location", "span", "sstream",
    "stack", "stdexcept", "stop_token", "streambuf", "string", "string_view", "strstream",
    "syncstream", "system_error", "thread", "tuple", "type_traits", "typeindex", "typeinfo",
    "unordered_map", "unordered_set", "utility", "valarray", "variant", "vector", "version",
    // the C library, both spellings
    "cassert", "cctype", "cerrno", "cfenv", "cfloat", "cinttypes", "climits", "clocale", "cmath",
    "csetjmp", "csignal", "cstdarg", "cstddef", "cstdint", "cstdio", "cstdlib", "cstring", "ctime",
    "cuchar", "cwchar", "cwctype", "assert.h", "ctype.h", "errno.h", "fenv.h", "float.h",
    "inttypes.h", "limits.h", "locale.h", "math.h", "setjmp.h", "signal.h", "stdarg.h", "stddef.h",
    "stdint.h", "stdio.h", "stdlib.h", "string.h", "time.h", "uchar.h", "wchar.h", "wctype.h",
    // GCC's header of every standard header, which many students know from contests
    "bits/stdc++.h"};

// Macros and names by which code could tell the plain build from the sanitized one.
constexpr std::array build_telling = {"NDEBUG",
                                      "__OPTIMIZE__",
                                      "__OPTIMIZE_SIZE__",
                                      "__NO_INLINE__",
                                      "__has_feature",
                                      "__has_extension",
                                      "_FORTIFY_SOURCE",
                                      "_GLIBCXX_ASSERTIONS",
                                      "_GLIBCXX_DEBUG",
                                      "EIGEN_NO_DEBUG",
                                      "EIGEN_MALLOC_ALREADY_ALIGNED",
                                      "__FAST_MATH__"};
constexpr std::array build_telling_prefixes = {"__SANITIZE", "__asan", "__ubsan", "__lsan",
                                               "__sanitizer"};

constexpr std::array allowed_directives = {"define",  "undef",   "if",       "ifdef",  "ifndef",
                                           "elif",    "elifdef", "elifndef", "else",   "endif",
                                           "include", "pragma",  "error",    "warning"};

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

std::string asm_text() {
  return "inline assembler is not allowed: a submission is C++ only (the assembler reads any "
         "file it is told to and puts any bytes among the code)";
}
std::string attribute_text(std::string_view name) {
  return "the compiler attribute " + std::string(name) +
         " is not allowed: attributes can place data among the code or switch the sanitizers "
         "off (the standard ones, [[nodiscard]], [[maybe_unused]], [[fallthrough]], ..., are "
         "fine)";
}
std::string build_telling_text(std::string_view name) {
  return std::string(name) +
         " tells one build of your code from the other (plain, and with the sanitizers): a "
         "submission must compute the same thing in both, so it may not use it";
}
std::string pragma_text(std::string_view pragma) {
  return "#pragma " + std::string(pragma) +
         " is not allowed: a pragma changes how the code is built (#pragma once and #pragma GCC "
         "diagnostic are fine)";
}

std::optional<std::string> identifier_breach(std::string_view id) {
  if (id == "asm" || id == "__asm" || id == "__asm__") return asm_text();
  if (id == "__attribute__" || id == "__attribute" || id == "__declspec") return attribute_text(id);
  if (id == "_Pragma")
    return std::string("_Pragma is not allowed: a pragma changes how the code is built");
  for (const char* name : build_telling)
    if (id == name) return build_telling_text(id);
  for (const char* prefix : build_telling_prefixes)
    if (starts_with(id, prefix)) return build_telling_text(id);
  return std::nullopt;
}

std::string include_text(const std::string& name) {
  if (name.find("catch2") != std::string::npos || name.find("catch.hpp") != std::string::npos)
    return "it includes Catch2 (" + name +
           "): a submission holds the task's functions, never tests of its own";
  return "it includes " + name +
         ", which a submission may not: only the C++ standard library (<vector>, <cmath>, ...), "
         "Eigen (<Eigen/Core>, ...), the kit's headers (\"springlab/...\") and this task's own "
         "files";
}

// What an #include names may be included: checked on the text as written, every #include,
// whether or not an #if skips it (what the preprocessor did include is checked again in its
// output, check_preprocessed).
std::optional<std::string> include_breach(std::string_view operands) {
  const auto start = operands.find_first_not_of(" \t");
  if (start == std::string_view::npos || (operands[start] != '<' && operands[start] != '"'))
    return std::string(
        "an #include must name its file in quotes or angle brackets, not "
        "through a macro");
  const char close = operands[start] == '<' ? '>' : '"';
  const auto end = operands.find(close, start + 1);
  if (end == std::string_view::npos) return std::string("an #include without its closing ") + close;
  const std::string name(operands.substr(start + 1, end - start - 1));
  const bool own = close == '"' && name.find_first_of("/\\") == std::string::npos &&
                   !name.empty() && name.front() != '.';
  const bool kit_or_eigen = (starts_with(name, "Eigen/") || starts_with(name, "springlab/")) &&
                            name.find("..") == std::string::npos;
  if (is_standard_header(name) || kit_or_eigen || own) return std::nullopt;
  return include_text(name);
}

std::optional<std::string> pragma_breach(std::string_view operands) {
  std::string words;
  for (const char c : operands) {
    if (c == '/') break;  // a comment after the pragma
    words += c;
  }
  const auto first = words.find_first_not_of(" \t");
  words = first == std::string::npos ? "" : words.substr(first);
  while (!words.empty() && std::isspace(static_cast<unsigned char>(words.back())))
    words.pop_back();
  if (words == "once" || starts_with(words, "GCC diagnostic ")) return std::nullopt;
  return pragma_text(words);
}

// Checks one file's tokens; returns the breach's line and words.
std::optional<std::pair<int, std::string>> check_text(const std::string& source) {
  Lexer lexer(source);
  Token t, previous{Token::punctuator, "", 0}, before{Token::punctuator, "", 0};
  int attribute_depth = 0;  // inside [[ ... ]]
  while (lexer.next(t)) {
    if (t.kind == Token::directive) {
      if (t.text.empty()) continue;  // the null directive
      if (std::find(allowed_directives.begin(), allowed_directives.end(), t.text) ==
          allowed_directives.end())
        return std::pair{t.line, "#" + t.text + " is not allowed in a submission"};
      if (t.text == "pragma")
        if (auto breach = pragma_breach(lexer.rest_of_line())) return std::pair{t.line, *breach};
      if (t.text == "include")
        if (auto breach = include_breach(lexer.rest_of_line())) return std::pair{t.line, *breach};
      previous = before = {Token::punctuator, "", t.line};
      continue;
    }
    if (t.kind == Token::identifier) {
      if (auto breach = identifier_breach(t.text)) return std::pair{t.line, *breach};
      if (attribute_depth > 0 && t.text == "using")
        return std::pair{t.line, attribute_text("[[using ...]]")};
    }
    if (t.kind == Token::punctuator) {
      if (t.text == "[" && previous.kind == Token::punctuator && previous.text == "[" &&
          attribute_depth == 0)
        attribute_depth = 1;
      else if (t.text == "]" && attribute_depth > 0)
        attribute_depth = 0;
      // [[gnu::section(...)]]: an attribute of a vendor's namespace
      if (attribute_depth > 0 && t.text == ":" && previous.text == ":" &&
          before.kind == Token::identifier)
        return std::pair{t.line, attribute_text("[[" + before.text + "::...]]")};
    }
    before = previous;
    previous = t;
  }
  return std::nullopt;
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

bool is_within(const fs::path& file, const fs::path& folder) {
  const auto [end, _] = std::mismatch(folder.begin(), folder.end(), file.begin(), file.end());
  return end == folder.end();
}

std::string PolicyBreach::text() const {
  return file + ":" + std::to_string(line) + ": " + what;
}

bool is_standard_header(std::string_view name) {
  return std::find(standard_headers.begin(), standard_headers.end(), name) !=
         standard_headers.end();
}

std::optional<PolicyBreach> check_sources(const fs::path& copy,
                                          const std::vector<std::string>& files) {
  for (const std::string& name : files)
    if (auto breach = check_text(read_file(copy / name)))
      return PolicyBreach{name, breach->first, breach->second};
  return std::nullopt;
}

namespace {

// A line marker, '# LINE "FILE" FLAGS...', as GCC writes them.
struct Marker {
  int line = 0;
  std::string file;
  bool enters = false, returns = false;
};

std::optional<Marker> read_marker(const std::string& text) {
  if (text.size() < 4 || text[0] != '#' || text[1] != ' ' ||
      !std::isdigit(static_cast<unsigned char>(text[2])))
    return std::nullopt;
  Marker m;
  std::size_t i = 2;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])))
    m.line = m.line * 10 + (text[i++] - '0');
  if (text.compare(i, 2, " \"") != 0) return std::nullopt;
  for (i += 2; i < text.size() && text[i] != '"'; ++i) {
    if (text[i] == '\\' && i + 1 < text.size()) ++i;  // GCC escapes quotes and backslashes
    m.file += text[i];
  }
  const std::string flags = i + 1 < text.size() ? text.substr(i + 1) : "";
  m.enters = flags.rfind(" 1", 0) == 0;
  m.returns = flags.rfind(" 2", 0) == 0;
  return m;
}

// Why a copy's file may not include `header`, or "".
std::string header_problem(const fs::path& header, const IncludeRoots& roots) {
  if (is_within(header, roots.copy)) return "";
  if (is_within(header, roots.kit_headers / "springlab")) return "";
  for (const fs::path& dir : roots.standard)
    if (is_within(header, dir) && is_standard_header(header.lexically_relative(dir).string()))
      return "";
  for (const fs::path& dir : roots.eigen)
    if (is_within(header, dir) && starts_with(header.lexically_relative(dir).string(), "Eigen/"))
      return "";
  std::string name = header.filename().string();
  for (const auto& dirs : {roots.standard, roots.eigen})
    for (const fs::path& dir : dirs)
      if (is_within(header, dir)) name = header.lexically_relative(dir).string();
  return include_text(name);
}

}  // namespace

Preprocessed check_preprocessed(std::istream& output, const IncludeRoots& roots) {
  Preprocessed result;
  struct Open {
    fs::path file;
    int line = 0;
  };
  std::vector<Open> stack{{"", 0}};
  std::string chunk;  // consecutive lines of a copy's file, lexed together (raw strings)
  int chunk_line = 0;
  fs::path chunk_file;
  const auto own = [&](const fs::path& file) { return is_within(file, roots.copy); };
  const auto flush = [&] {
    if (!chunk.empty() && !result.breach)
      if (auto breach = check_text(chunk))
        result.breach = PolicyBreach{chunk_file.filename().string(), chunk_line + breach->first - 1,
                                     breach->second + " (written so through a macro)"};
    chunk.clear();
  };
  std::string text;
  while (!result.breach && std::getline(output, text)) {
    Open& top = stack.back();
    if (const auto marker = read_marker(text)) {
      flush();
      const fs::path file = fs::path(marker->file).lexically_normal();
      if (marker->enters) {
        if (own(top.file)) {
          if (std::string problem = header_problem(file, roots); !problem.empty()) {
            result.breach = PolicyBreach{top.file.filename().string(), top.line, problem};
            break;
          }
        }
        if (own(file) && std::find(result.own_files.begin(), result.own_files.end(),
                                   file.filename().string()) == result.own_files.end())
          result.own_files.push_back(file.filename().string());
        stack.push_back({file, marker->line});
      } else {
        if (marker->returns && stack.size() > 1) stack.pop_back();
        stack.back().file = file;
        stack.back().line = marker->line;
      }
      continue;
    }
    if (own(top.file)) {
      if (chunk.empty()) {
        chunk_line = top.line;
        chunk_file = top.file;
      }
      // What the preprocessor passes on of a pragma is its directive: checked as written.
      chunk += text + '\n';
    }
    ++top.line;
  }
  flush();
  return result;
}

}  // namespace springlab::grader
