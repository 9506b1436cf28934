#include "policy.hpp"

#include "cpp_lexer.hpp"
#include "process.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

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
// The policy's own preprocessing reads empty stand-ins for the headers (stand_in_flags), which
// __has_include would see through: it could take one branch there and another in the build.
std::string has_include_text(std::string_view name) {
  return std::string(name) +
         " is not allowed: a submission includes the headers it needs, without asking which "
         "files the grader's machine holds";
}
std::string line_marker_text() {
  return "a line marker (#line, or # and a number) is not allowed: it tells the compiler that the "
         "lines after it come from another file or line, which would hide them from the "
         "grader's checks";
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
  if (id == "__has_include" || id == "__has_include_next") return has_include_text(id);
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
      if (t.text == "line" || std::isdigit(static_cast<unsigned char>(t.text[0])))
        return std::pair{t.line, line_marker_text()};
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

std::string control_text(unsigned char c) {
  static const char* const digits = "0123456789ABCDEF";
  const std::string byte = {'0', 'x', digits[c >> 4], digits[c & 15]};
  return std::string(c == 0 ? "a NUL byte" : "a control character") + " (" + byte +
         ") is not allowed in a source file: an editor does not show it, and the compiler may "
         "read it otherwise than the grader's checks would; save the file as plain text";
}

std::string lone_return_text() {
  return "a carriage return that does not end a line is not allowed: the compiler takes it "
         "for a line break where an editor may show none, and it could make the compiler and "
         "the grader's checks read the code differently; save the file with ordinary line ends";
}

// Bytes on which a reading of the text and the compiler's may differ: GCC takes NUL and
// vertical tab for blanks (also right after '#', and between a backslash and the end of a line)
// and a carriage return alone for a line break; no other control character belongs in C++
// source, so none is let through for a reading to disagree on. Tab, form feed
// and the carriage return of a CRLF line end are ordinary text (the kit's lexer reads them as
// GCC does). Bytes from 0x80 up are left alone: comments in other languages are UTF-8, or an
// older encoding, and GCC never takes such a byte for a blank or a line break.
std::optional<std::pair<int, std::string>> character_breach(std::string_view text) {
  int line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
    } else if (c == '\r') {
      if (i + 1 == text.size() || text[i + 1] != '\n') return std::pair{line, lone_return_text()};
    } else if ((c < 0x20 && c != '\t' && c != '\f') || c == 0x7f) {
      return std::pair{line, control_text(c)};
    }
  }
  return std::nullopt;
}

// A file's text as the compiler reads it from its first byte: GCC drops a leading UTF-8 byte
// order mark, so the checks drop it too (ignoring it instead would leave it glued to the first
// line, and a directive there unseen).
std::string without_byte_order_mark(std::string text) {
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  return text;
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
  for (const std::string& name : files) {
    const std::string text = without_byte_order_mark(read_file(copy / name));
    if (auto breach = character_breach(text))
      return PolicyBreach{name, breach->first, breach->second};
    if (auto breach = check_text(text)) return PolicyBreach{name, breach->first, breach->second};
  }
  return std::nullopt;
}

namespace {

// A line marker, '# LINE "FILE" FLAGS...', as GCC writes them.
struct Marker {
  int line = 0;
  std::string file;
  bool enters = false, returns = false, system = false;
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
  std::istringstream flags(i + 1 < text.size() ? text.substr(i + 1) : "");
  for (int flag = 0; flags >> flag;) {
    m.enters = m.enters || flag == 1;
    m.returns = m.returns || flag == 2;
    m.system = m.system || flag == 3;
  }
  return m;
}

// Where the preprocessor's output is, by its line markers, and whether each marker is one the
// preprocessor made: after the first lines (the command line's), it enters a file and returns
// to the one that included it, and otherwise names only the file it is in (to skip blank
// lines). A marker that names another file without entering or leaving one was written in the
// source, whatever the file it names.
class MarkerWalk {
 public:
  struct Open {
    fs::path file;
    int line = 0;
  };
  const Open& top() const { return stack_.back(); }
  Open& top() { return stack_.back(); }
  /// True once the output has reached the first line of the file preprocessed.
  bool started() const { return started_; }
  /// Follows `m` (its file lexically normal); false when the preprocessor did not make it. Only
  /// where `checked` (a system header's own markers are its business).
  bool follow(const Marker& m, const fs::path& file, bool checked = true) {
    if (++markers_ == 1) main_ = file;
    const bool rename = !m.enters && !m.returns;
    const bool check = started_ && checked;
    if (check && rename && file != top().file) return false;
    if (check && m.returns && (stack_.size() < 2 || stack_[stack_.size() - 2].file != file))
      return false;
    if (m.enters) stack_.push_back({file, m.line});
    if (m.returns && stack_.size() > 1) stack_.pop_back();
    if (!m.enters) top() = {file, m.line};
    started_ = started_ || (markers_ > 1 && rename && file == main_);
    return true;
  }

 private:
  std::vector<Open> stack_{{"", 0}};
  int markers_ = 0;
  fs::path main_;
  bool started_ = false;
};

// The lines of one file of the copy that the output shows in a row, checked together (a raw
// string may span them) once the next marker or the end comes.
struct Chunk {
  std::string text;
  fs::path file;
  int line = 0;
  void add(const MarkerWalk::Open& at, const std::string& output_line) {
    if (text.empty()) {
      file = at.file;
      line = at.line;
    }
    text += output_line + '\n';
  }
  // The chunk's first breach, and then an empty chunk.
  std::optional<PolicyBreach> flush() {
    std::optional<PolicyBreach> result;
    if (!text.empty())
      if (auto breach = check_text(text))
        result = PolicyBreach{file.filename().string(), line + breach->first - 1,
                              breach->second + " (written so through a macro)"};
    text.clear();
    return result;
  }
};

void add_own_file(Preprocessed& result, const fs::path& file) {
  const std::string name = file.filename().string();
  if (std::find(result.own_files.begin(), result.own_files.end(), name) == result.own_files.end())
    result.own_files.push_back(name);
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

// What one preprocessing's output allows; the walk over it (walk_output) is the same for all.
struct OutputRules {
  std::function<bool(const fs::path&)> own;  ///< a file of the copy
  /// Follows a line marker on `walk`; why it may not be there, or nothing.
  std::function<std::optional<std::string>(const Marker&, const fs::path&, MarkerWalk&)> marker;
  std::function<bool(const MarkerWalk&)> checks_line;  ///< an output line is the copy's, checked
};

// Reads a preprocessor's output: every line marker judged by `rules`, every line of the copy
// checked (in chunks: a raw string may span lines), the copy's files entered listed. Stops at
// the first breach.
Preprocessed walk_output(std::istream& output, const OutputRules& rules) {
  Preprocessed result;
  MarkerWalk walk;
  Chunk chunk;
  std::string text;
  while (!result.breach && std::getline(output, text)) {
    if (const auto marker = read_marker(text)) {
      result.breach = chunk.flush();
      const fs::path file = fs::path(marker->file).lexically_normal();
      const MarkerWalk::Open at = walk.top();
      if (const auto why = rules.marker(*marker, file, walk)) {
        result.breach = PolicyBreach{at.file.filename().string(), at.line, *why};
        break;
      }
      if (marker->enters && rules.own(file)) add_own_file(result, file);
      continue;
    }
    if (rules.checks_line(walk)) chunk.add(walk.top(), text);
    ++walk.top().line;
  }
  if (!result.breach) result.breach = chunk.flush();
  return result;
}

}  // namespace

Preprocessed check_preprocessed(std::istream& output, const IncludeRoots& roots) {
  OutputRules rules;
  rules.own = [&](const fs::path& file) { return is_within(file, roots.copy); };
  rules.marker = [&](const Marker& m, const fs::path& file,
                     MarkerWalk& walk) -> std::optional<std::string> {
    const bool from_copy = rules.own(walk.top().file);
    if (m.enters && from_copy)
      if (std::string problem = header_problem(file, roots); !problem.empty()) return problem;
    if (!walk.follow(m, file, from_copy)) return line_marker_text();
    return std::nullopt;
  };
  // What the preprocessor passes on of a pragma is its directive: checked as written.
  rules.checks_line = [&](const MarkerWalk& walk) { return rules.own(walk.top().file); };
  return walk_output(output, rules);
}

namespace {

// The number of lines of a file of the copy (a line marker may not name a later one).
int line_count(const fs::path& file) {
  const std::string text = read_file(file);
  return int(std::count(text.begin(), text.end(), '\n')) + 1;
}

// A marker that MarkerWalk lets pass but the policy's own preprocessing never makes: there, no
// header is a system header (nothing is included by -isystem), files are entered only from the
// copy and the stand-ins, and a line number never lies past the end of its file.
bool stand_in_marker_forged(const Marker& m, const fs::path& file, const fs::path& copy,
                            const StandIns& stand_ins, std::map<fs::path, int>& lines) {
  if (m.system) return true;
  if (m.enters) return !is_within(file, copy) && !is_within(file, stand_ins.folder);
  if (!is_within(file, copy)) return false;
  if (lines.count(file) == 0) lines[file] = line_count(file);
  return m.line > lines[file];
}

}  // namespace

Preprocessed check_stand_in_output(std::istream& output, const fs::path& copy,
                                   const StandIns& stand_ins) {
  std::map<fs::path, int> lines;
  OutputRules rules;
  rules.own = [&](const fs::path& file) { return is_within(file, copy); };
  rules.marker = [&](const Marker& m, const fs::path& file,
                     MarkerWalk& walk) -> std::optional<std::string> {
    const bool started = walk.started();
    if (!walk.follow(m, file) ||
        (started && stand_in_marker_forged(m, file, copy, stand_ins, lines)))
      return line_marker_text();
    return std::nullopt;
  };
  // Every line after the command line's is the copy's: the stand-ins are empty.
  rules.checks_line = [](const MarkerWalk& walk) { return walk.started(); };
  return walk_output(output, rules);
}

std::vector<std::string> stand_in_flags(const std::vector<std::string>& compile,
                                        const StandIns& stand_ins) {
  std::vector<std::string> flags;
  for (std::size_t i = 0; i < compile.size(); ++i) {
    const std::string& flag = compile[i];
    if (flag == "-isystem" || flag == "-include" || flag == "-iquote" || flag == "-idirafter" ||
        flag == "-I") {
      ++i;  // and its folder or file
      continue;
    }
    if (starts_with(flag, "-I") || flag == "-Winvalid-pch") continue;
    flags.push_back(flag);
  }
  for (const std::string& flag : {std::string("-nostdinc"), "-I" + stand_ins.folder.string(),
                                  std::string("-fno-working-directory")})
    flags.push_back(flag);
  return flags;
}

std::string added_definitions(const std::string& with, const std::string& without) {
  std::set<std::string> known;
  std::istringstream before(without), after(with);
  for (std::string line; std::getline(before, line);)
    known.insert(line);
  std::string added;
  for (std::string line; std::getline(after, line);)
    if (known.count(line) == 0) added += line + '\n';
  return added;
}

void write_stand_ins(const StandIns& stand_ins, const IncludeRoots& roots,
                     const std::string& macros) {
  const auto stand_in = [&](const fs::path& name) {
    const fs::path file = stand_ins.folder / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::trunc);
  };
  for (const char* name : standard_headers)
    stand_in(name);
  // Eigen's and the kit's headers by the names they have on disk, so that a name that is not
  // there fails here as it does in the build.
  const auto mirror = [&](const fs::path& dir, const fs::path& sub) {
    std::error_code error;
    for (const auto& entry : fs::recursive_directory_iterator(dir / sub, error))
      if (entry.is_regular_file()) stand_in(sub / entry.path().lexically_relative(dir / sub));
  };
  mirror(roots.kit_headers, "springlab");
  for (const fs::path& dir : roots.eigen)
    mirror(dir, "Eigen");
  std::ofstream(stand_ins.macros, std::ios::trunc) << macros;
  // Readable by the user the sandbox runs commands as, whatever the umask.
  const fs::perms read = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                         fs::perms::others_read;
  const fs::perms enter = fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec;
  const fs::path root = stand_ins.folder.parent_path();
  fs::permissions(root, read | enter);
  for (const auto& entry : fs::recursive_directory_iterator(root))
    fs::permissions(entry.path(), entry.is_directory() ? read | enter : read);
}

StandIns prepare_stand_ins(const Kit& kit, const fs::path& folder) {
  fs::remove_all(folder);
  fs::create_directories(folder);
  const StandIns stand_ins{folder / "headers", folder / "macros.hpp"};
  IncludeRoots roots;
  roots.kit_headers = kit.headers;
  for (std::size_t i = 0; i + 1 < kit.plain.compile.size(); ++i)
    if (kit.plain.compile[i] == "-isystem") roots.eigen.emplace_back(kit.plain.compile[i + 1]);
  // Each listing written to a file: the compiler's warnings go elsewhere.
  const auto listing = [&](std::vector<std::string> argv, const fs::path& file) {
    for (const std::string arg : {"-dM", "-E", "-x", "c++", "/dev/null", "-o", file.c_str()})
      argv.push_back(arg);
    Command c;
    c.argv = std::move(argv);
    c.env = plain_environment();
    c.directory = folder.string();
    c.limits.file_size_mb = 32;
    Outcome outcome;
    ProcessPool pool(1);
    pool.add(std::move(c), [&](Outcome o) { outcome = std::move(o); });
    pool.run();
    if (!outcome.exited || outcome.exit_code != 0)
      throw std::runtime_error("the compiler could not list the macros of submission code: " +
                               outcome.start_error + outcome.output);
    std::string text = read_file(file);
    fs::remove(file);
    return text;
  };
  const std::string with = listing(kit.plain.compile, folder / "with.txt"),
                    without = listing(stand_in_flags(kit.plain.compile, stand_ins),
                                      folder / "without.txt");
  write_stand_ins(stand_ins, roots, added_definitions(with, without));
  return stand_ins;
}

}  // namespace springlab::grader
