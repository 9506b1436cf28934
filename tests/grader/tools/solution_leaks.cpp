// springlab-solution-leaks KIT FOLDER: looks for the body of every task function of KIT's
// solutions/ in every text file under FOLDER (a student release), normalised for names and
// spacing: comments and layout dropped, identifiers matched by a one-to-one renaming (a copy
// whose variables were renamed is still found), numbers by value. Prints each find as
// "leak: FILE:LINE: ..." and exits 1; exits 0 saying how much it looked through when there is
// none, 2 when it cannot read KIT's solutions. (.ci/release/leaks runs it beside its line checks.)
#include "cpp_lexer.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fs = std::filesystem;
using namespace springlab::grader;

namespace {

constexpr std::array keywords = {
    "alignas",  "alignof",  "auto",      "bool",      "break",    "case",          "catch",
    "char",     "class",    "const",     "constexpr", "continue", "decltype",      "default",
    "delete",   "do",       "double",    "else",      "enum",     "explicit",      "extern",
    "false",    "float",    "for",       "friend",    "if",       "inline",        "int",
    "long",     "mutable",  "namespace", "new",       "noexcept", "nullptr",       "operator",
    "return",   "short",    "signed",    "sizeof",    "static",   "static_assert", "static_cast",
    "struct",   "switch",   "template",  "this",      "throw",    "true",          "try",
    "typename", "unsigned", "using",     "void",      "volatile", "while"};

// A token as compared: identifiers by a renaming, numbers by value, the rest as written.
struct Word {
  enum Kind { name, number, other } kind = other;
  std::string text;
  int line = 0;
};

std::vector<Word> words(const std::string& source) {
  std::vector<Word> result;
  for (const Token& t : tokens(source)) {
    Word w{Word::other, t.text, t.line};
    if (t.kind == Token::identifier &&
        std::find(keywords.begin(), keywords.end(), t.text) == keywords.end())
      w.kind = Word::name;
    if (t.kind == Token::literal && !t.text.empty() &&
        (std::isdigit(t.text[0]) || t.text[0] == '.')) {
      std::string digits;
      for (const char c : t.text)
        if (c != '\'') digits += c;
      w.kind = Word::number;
      w.text = std::to_string(std::strtod(digits.c_str(), nullptr));
    }
    if (t.kind == Token::directive) w.text = "#" + t.text;
    result.push_back(std::move(w));
  }
  return result;
}

struct Body {
  std::string function, file;
  std::vector<Word> words;
};

// The bodies of the functions a solution file defines as springlab::NAME(...) { ... }.
std::vector<Body> bodies_of(const fs::path& file, const std::string& shown) {
  std::ifstream in(file);
  const std::vector<Word> w =
      words({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
  std::vector<Body> result;
  for (std::size_t i = 0; i + 4 < w.size(); ++i) {
    if (w[i].text != "springlab" || w[i + 1].text != ":" || w[i + 2].text != ":" ||
        w[i + 3].kind != Word::name || w[i + 4].text != "(")
      continue;
    std::size_t j = i + 4;
    for (int depth = 0; j < w.size(); ++j) {
      depth += w[j].text == "(" ? 1 : w[j].text == ")" ? -1 : 0;
      if (depth == 0) break;
    }
    while (j < w.size() && w[j].text != "{" && w[j].text != ";")
      ++j;
    if (j >= w.size() || w[j].text == ";") continue;
    std::size_t k = j;
    for (int depth = 0; k < w.size(); ++k) {
      depth += w[k].text == "{" ? 1 : w[k].text == "}" ? -1 : 0;
      if (depth == 0) break;
    }
    result.push_back({w[i + 3].text, shown, {w.begin() + long(j) + 1, w.begin() + long(k)}});
    i = k;
  }
  return result;
}

// True when `text` from `at` on is `body` with its names renamed one to one.
bool matches(const std::vector<Word>& body, const std::vector<Word>& text, std::size_t at) {
  if (at + body.size() > text.size()) return false;
  std::map<std::string, std::string> forward, backward;
  for (std::size_t n = 0; n < body.size(); ++n) {
    const Word &b = body[n], &t = text[at + n];
    if (b.kind != t.kind) return false;
    if (b.kind != Word::name) {
      if (b.text != t.text) return false;
      continue;
    }
    const auto [f, fresh_f] = forward.emplace(b.text, t.text);
    const auto [r, fresh_r] = backward.emplace(t.text, b.text);
    if (f->second != t.text || r->second != b.text) return false;
  }
  return true;
}

bool is_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char start[8192];
  in.read(start, sizeof start);
  return std::find(start, start + in.gcount(), '\0') == start + in.gcount();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: springlab-solution-leaks KIT FOLDER\n";
    return 2;
  }
  const fs::path kit = argv[1], folder = argv[2];
  std::vector<Body> bodies;
  std::error_code error;
  for (const auto& entry : fs::recursive_directory_iterator(kit / "solutions", error))
    if (entry.path().extension() == ".cpp")
      for (Body& b : bodies_of(entry.path(), entry.path().lexically_relative(kit).string()))
        bodies.push_back(std::move(b));
  if (bodies.empty()) {
    std::cerr << "springlab-solution-leaks: no solution function found in " << kit / "solutions"
              << "\n";
    return 2;
  }
  int files = 0, leaks = 0;
  for (auto it = fs::recursive_directory_iterator(folder, error);
       it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (it->is_directory() && it->path().filename() == ".git") {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || !is_text(it->path())) continue;
    ++files;
    std::ifstream in(it->path());
    const std::vector<Word> text =
        words({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
    for (const Body& b : bodies)
      for (std::size_t at = 0; !b.words.empty() && at < text.size(); ++at)
        if (matches(b.words, text, at)) {
          std::cerr << "leak: " << it->path().string() << ":" << text[at].line << ": the body of "
                    << b.function << " (" << b.file << "), names or spacing changed or not\n";
          ++leaks;
        }
  }
  if (leaks > 0) return 1;
  std::cout << "solution-leaks: none (" << bodies.size() << " solution functions' bodies looked "
            << "for in " << files << " text files, names and spacing aside)\n";
  return 0;
}
