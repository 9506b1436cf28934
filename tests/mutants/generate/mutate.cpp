// springlab-mutate: mistakes nobody listed, made by rule, to measure how well the tests' feedback
// names mistakes it was not written for (issue 25's measure).
//
//   springlab-mutate generate KIT OUT
//       Mutates each task function of KIT/solutions/ by systematic rules, one change per mutant:
//       an arithmetic or compound-assignment operator swapped, a comparison loosened or
//       tightened, a unary minus dropped, a constant changed, a call's two arguments swapped, a
//       name replaced by another of its kind (r_p/r_q, rows/cols, k/b, .p/.q, ...), a statement
//       deleted. Each mutant is OUT/submissions/<id>/ (a copy of the solutions with the one file
//       changed) and a line of OUT/manifest.tsv: id, half, task, file, line, rule, what changed.
//       The half (A or B) comes from a hash of the id, fixed before anything is built or graded:
//       A tunes the feedback, B measures it.
//   springlab-mutate judge OUT RESULTS HALF
//       Reads the grader's RESULTS folder (one folder per mutant) for the mutants of HALF: a
//       mutant counts when it compiled and lost points in its own task; it is named when its
//       task's first failure has a "likely mistake:" line (or, where no cause was checked, a
//       "measured:" one) about the function it changed (its name or an equation of its), wrong
//       when that line is about another function only. Prints a
//       line per mutant and the totals.
#include "cpp_lexer.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using springlab::grader::Lexer;
using springlab::grader::Token;

namespace {

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A token with its place in the text (the solutions have no line splices, so the lexer's text is
// the file's).
struct Placed {
  Token token;
  std::size_t at = 0;
};

std::vector<Placed> placed_tokens(const std::string& text) {
  std::vector<Placed> result;
  Lexer lexer(text);
  for (Token t; lexer.next(t);)
    result.push_back({t, t.offset});
  return result;
}

struct Mutant {
  std::string id, task_folder, file, function, rule, what;
  int line = 0;
  std::string text;  // the mutated file
};

// Names that may stand for one another: a mistake that uses one where the other belongs.
const std::vector<std::set<std::string>> kinds = {
    {"r_p", "r_q"},   {"v_p", "v_q"}, {"k", "b", "rest_length"},
    {"rows", "cols"}, {"row", "col"}, {"p", "q"},
    {"r", "v"},       {"h"}};

std::string function_of(const std::vector<Placed>& tokens, std::size_t at) {
  std::string name;
  for (std::size_t i = 0; i + 3 < tokens.size() && tokens[i].at <= at; ++i)
    if (tokens[i].token.text == "springlab" && tokens[i + 1].token.text == ":" &&
        tokens[i + 2].token.text == ":" && tokens[i + 3].token.kind == Token::identifier)
      name = tokens[i + 3].token.text;
  return name;
}

// The spans [begin, end) of the function bodies: only their tokens are mutated.
std::vector<std::pair<std::size_t, std::size_t>> bodies(const std::vector<Placed>& t) {
  std::vector<std::pair<std::size_t, std::size_t>> result;
  for (std::size_t i = 0; i + 4 < t.size(); ++i) {
    if (t[i].token.text != "springlab" || t[i + 1].token.text != ":" ||
        t[i + 3].token.kind != Token::identifier || t[i + 4].token.text != "(")
      continue;
    std::size_t j = i + 4;
    for (int depth = 0; j < t.size(); ++j) {
      depth += t[j].token.text == "(" ? 1 : t[j].token.text == ")" ? -1 : 0;
      if (depth == 0) break;
    }
    while (j < t.size() && t[j].token.text != "{" && t[j].token.text != ";")
      ++j;
    if (j >= t.size() || t[j].token.text == ";") continue;
    std::size_t k = j;
    for (int depth = 0; k < t.size(); ++k) {
      depth += t[k].token.text == "{" ? 1 : t[k].token.text == "}" ? -1 : 0;
      if (depth == 0) break;
    }
    result.push_back({j + 1, k});
    i = k;
  }
  return result;
}

bool operand_end(const Token& t) {
  return t.kind == Token::identifier || t.kind == Token::literal || t.text == ")" || t.text == "]";
}

std::vector<Mutant> mutants_of(const fs::path& file, const std::string& task_folder) {
  const std::string text = read(file);
  const std::vector<Placed> t = placed_tokens(text);
  std::vector<Mutant> out;
  const auto line_of = [&](std::size_t at) {
    return int(std::count(text.begin(), text.begin() + long(at), '\n')) + 1;
  };
  const auto add = [&](std::size_t at, std::size_t length, const std::string& with,
                       const std::string& rule) {
    Mutant m;
    m.task_folder = task_folder;
    m.file = file.filename().string();
    m.function = function_of(t, at);
    m.rule = rule;
    m.line = line_of(at);
    std::string was = text.substr(at, length);
    for (char& ch : was)
      if (ch == '\n' || ch == '\t') ch = ' ';
    m.what = "'" + was + "' -> '" + with + "'";
    m.text = text.substr(0, at) + with + text.substr(at + length);
    out.push_back(std::move(m));
  };
  for (const auto& [begin, end] : bodies(t)) {
    for (std::size_t i = begin; i < end; ++i) {
      const Token& x = t[i].token;
      const Token* before = i > begin ? &t[i - 1].token : nullptr;
      const Token* after = i + 1 < end ? &t[i + 1].token : nullptr;
      const bool binary = before && operand_end(*before);
      // Compound assignments and comparisons are two punctuators.
      const bool then_equals = after && after->text == "=" && t[i + 1].at == t[i].at + 1;
      if ((x.text == "+" || x.text == "-") && then_equals)
        add(t[i].at, 2, x.text == "+" ? "-=" : "+=", "compound assignment swapped");
      else if ((x.text == "+" || x.text == "-") && binary && !(after && after->text == x.text) &&
               !(before && before->text == x.text))
        add(t[i].at, 1, x.text == "+" ? "-" : "+", "arithmetic operator swapped");
      else if (x.text == "-" && !binary && !(after && after->text == "-") &&
               !(before && before->text == "-"))
        add(t[i].at, 1, "", "unary minus dropped");
      else if (x.text == "*" && binary)
        add(t[i].at, 1, "/", "arithmetic operator swapped");
      else if (x.text == "/" && binary)
        add(t[i].at, 1, "*", "arithmetic operator swapped");
      // Comparisons in conditions: < and <=, > and >=, == and !=.
      if ((x.text == "<" || x.text == ">") && binary && after &&
          (after->kind == Token::identifier || after->kind == Token::literal ||
           after->text == "=")) {
        const bool or_equal = then_equals;
        // Template arguments (std::vector<Spring>) are not comparisons: a type name follows.
        if (!or_equal && after->kind == Token::identifier && std::isupper(after->text[0])) continue;
        if (or_equal)
          add(t[i].at, 2, x.text, "comparison tightened");
        else
          add(t[i].at, 1, x.text + "=", "comparison loosened");
      }
      if (x.text == "=" && before && before->text == "=" && t[i - 1].at + 1 == t[i].at)
        add(t[i - 1].at, 2, "!=", "comparison negated");
      // Constants.
      if (x.kind == Token::literal && std::isdigit(static_cast<unsigned char>(x.text[0]))) {
        const double value = std::strtod(x.text.c_str(), nullptr);
        const bool real = x.text.find('.') != std::string::npos;
        std::vector<std::string> others;
        if (value == 0.0) others = {real ? "1.0" : "1"};
        if (value == 1.0) others = {real ? "2.0" : "2", real ? "0.0" : "0"};
        if (value == 2.0) others = {real ? "1.0" : "1", real ? "4.0" : "3"};
        if (value == 0.5) others = {"1.0", "0.25"};
        for (const std::string& other : others)
          add(t[i].at, x.text.size(), other, "constant changed");
      }
      // A name where another of its kind belongs.
      if (x.kind == Token::identifier)
        for (const auto& kind : kinds)
          if (kind.count(x.text) > 0)
            for (const std::string& other : kind)
              if (other != x.text) add(t[i].at, x.text.size(), other, "name replaced");
      // A call's first two arguments swapped: f(a, b, ...) with a and b single names.
      if (x.kind == Token::identifier && after && after->text == "(" && i + 4 < end &&
          t[i + 2].token.kind == Token::identifier && t[i + 3].token.text == "," &&
          t[i + 4].token.kind == Token::identifier &&
          (t[i + 5].token.text == "," || t[i + 5].token.text == ")")) {
        const std::size_t a = t[i + 2].at, b_end = t[i + 4].at + t[i + 4].token.text.size();
        add(a, b_end - a, t[i + 4].token.text + ", " + t[i + 2].token.text, "arguments swapped");
      }
      // A statement deleted: from after the previous ; { or } to its ;.
      if (x.text == ";") {
        std::size_t s = i;
        while (s > begin && t[s - 1].token.text != ";" && t[s - 1].token.text != "{" &&
               t[s - 1].token.text != "}")
          --s;
        // Not a declaration (a type, const or auto first): the rest would not compile.
        const Token& first = t[s].token;
        const bool declaration = first.text == "const" || first.text == "auto" ||
                                 (first.kind == Token::identifier && std::isupper(first.text[0])) ||
                                 first.text == "double" || first.text == "int" ||
                                 first.text == "for" || first.text == "return";
        if (!declaration && s < i) add(t[s].at, t[i].at + 1 - t[s].at, "", "statement deleted");
      }
    }
  }
  return out;
}

std::uint64_t fnv(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : text)
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return hash;
}

int generate(const fs::path& kit, const fs::path& out) {
  fs::remove_all(out);
  fs::create_directories(out / "submissions");
  std::ofstream manifest(out / "manifest.tsv");
  manifest << "id\thalf\ttask\tfile\tfunction\tline\trule\twhat\n";
  std::map<std::string, int> count;
  std::set<std::string> seen;  // two rules giving the same text are one mutant
  std::vector<fs::path> files;
  for (const auto& folder : fs::directory_iterator(kit / "solutions"))
    for (const auto& file : fs::directory_iterator(folder.path()))
      if (file.path().extension() == ".cpp") files.push_back(file.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    const std::string task_folder = file.parent_path().filename().string();
    for (Mutant& m : mutants_of(file, task_folder)) {
      if (!seen.insert(m.task_folder + "/" + m.file + "\n" + m.text).second) continue;
      m.id = "m" + std::string(1, task_folder[4]) + "-" + fs::path(m.file).stem().string() + "-" +
             std::to_string(++count[m.file]);
      const char half = fnv(m.id + m.what) % 2 == 0 ? 'A' : 'B';
      const fs::path target = out / "submissions" / m.id;
      fs::copy(kit / "solutions", target, fs::copy_options::recursive);
      std::ofstream(target / task_folder / m.file, std::ios::binary) << m.text;
      manifest << m.id << '\t' << half << '\t' << task_folder[4] << '\t' << task_folder << "/"
               << m.file << '\t' << m.function << '\t' << m.line << '\t' << m.rule << '\t' << m.what
               << '\n';
    }
  }
  std::cout << "springlab-mutate: " << seen.size() << " mutants in " << out << "\n";
  return 0;
}

// The words by which feedback names a function: its name and its equations.
const std::map<std::string, std::vector<std::string>> names_of = {
    {"spring_force", {"spring_force", "(1.1)", "spring force"}},
    {"damper_force", {"damper_force", "(1.2)", "damper force"}},
    {"explicit_euler_step", {"explicit_euler_step", "(1.4)", "(1.5)", "the step"}},
    {"structural_springs", {"structural_springs", "(2.2)", "(2.1)"}},
    {"accumulate_spring_forces",
     {"accumulate_spring_forces", "(2.3)", "(2.4)", "dampers' power", "spring forces"}},
    {"shear_springs", {"shear_springs", "(3.1)", "(3.2)"}},
    {"verlet_step", {"verlet_step", "(4.", "Verlet", "the step", "r_{-1}", "r_{n+1}"}},
    {"bend_springs", {"bend_springs", "(5.1)"}},
    {"add_gravity", {"add_gravity", "(5.2)", "gravity"}},
    {"add_wind", {"add_wind", "(5.3)", "(5.4)", "wind"}},
    {"hold_pinned", {"hold_pinned", "(5.5)", "pinned"}}};

// The first failure of task `task` in a feedback.txt: from the first " ... FAIL" line to the next
// test's line.
std::string first_failure(const std::string& feedback, int task) {
  const std::string heading = "==> Task " + std::to_string(task) + ":";
  auto at = feedback.find(heading);
  if (at == std::string::npos) return "";
  const auto end = feedback.find("\n==> ", at + 1);
  const std::string section = feedback.substr(at, end == std::string::npos ? end : end - at);
  const auto fail = section.find(" ... FAIL\n");
  if (fail == std::string::npos)
    return section.find("not graded") != std::string::npos ||
                   section.find("does not compile") != std::string::npos
               ? section
               : "";
  // The next test's line: two spaces of indent, where a failure's own lines have eight (they may
  // hold " ... " too: "(5 in all)" lists).
  const auto begin = section.rfind('\n', fail) + 1;
  auto line_start = section.find('\n', fail + 1);
  while (line_start != std::string::npos && section.compare(line_start + 1, 3, "   ") == 0)
    line_start = section.find('\n', line_start + 1);
  return section.substr(begin,
                        line_start == std::string::npos ? std::string::npos : line_start - begin);
}

int judge(const fs::path& out, const fs::path& results, char half) {
  std::ifstream manifest(out / "manifest.tsv");
  std::string line;
  std::getline(manifest, line);
  int counted = 0, named = 0, wrong = 0, not_compiling = 0, not_losing = 0;
  std::map<std::string, std::pair<int, int>> by_rule;  // counted, named
  while (std::getline(manifest, line)) {
    std::istringstream fields(line);
    std::string id, h, task, file, function, at, rule, what;
    std::getline(fields, id, '\t');
    std::getline(fields, h, '\t');
    std::getline(fields, task, '\t');
    std::getline(fields, file, '\t');
    std::getline(fields, function, '\t');
    std::getline(fields, at, '\t');
    std::getline(fields, rule, '\t');
    std::getline(fields, what, '\t');
    if (h.empty() || h[0] != half) continue;
    const std::string feedback = read(results / id / "feedback.txt");
    if (feedback.empty()) continue;
    const std::string first = first_failure(feedback, std::stoi(task));
    if (first.find("does not compile") != std::string::npos ||
        first.find("not graded") != std::string::npos) {
      ++not_compiling;
      continue;
    }
    if (first.empty()) {
      ++not_losing;
      continue;
    }
    ++counted;
    ++by_rule[rule].first;
    // A cause ("likely mistake:") or, where no concrete wrong version was checked, what was
    // measured ("measured:"): either is judged by what it is about.
    auto mistake_at = first.find("likely mistake: ");
    if (mistake_at == std::string::npos) mistake_at = first.find("measured: ");
    std::string verdict = "silent";
    // The verdict's own line (a crash or a limit) when it names the function or its file.
    const auto message_at = first.find('\n') + 1;
    const std::string message = first.substr(message_at, first.find('\n', message_at) - message_at);
    const std::string file_name = file.substr(file.find('/') + 1);
    const auto names_function = [&](const std::string& name) {
      return message.find(" in " + name) != std::string::npos ||
             message.find("your " + name + " ") != std::string::npos;
    };
    bool message_about_other = false;
    for (const auto& entry : names_of)
      if (entry.first != function && names_function(entry.first)) message_about_other = true;
    if (mistake_at == std::string::npos &&
        (message.find(file_name) != std::string::npos || names_function(function))) {
      verdict = "named";
      ++named;
      ++by_rule[rule].second;
    } else if (mistake_at == std::string::npos && message_about_other) {
      verdict = "WRONG";  // a crash or a limit put on another function
      ++wrong;
    } else if (mistake_at != std::string::npos) {
      const std::string mistake =
          first.substr(mistake_at, first.find('\n', mistake_at) - mistake_at);
      bool about_it = false, about_other = false;
      for (const auto& [name, words] : names_of)
        for (const std::string& w : words)
          if (mistake.find(w) != std::string::npos)
            (name == function ? about_it : about_other) = true;
      if (about_it) {
        verdict = "named";
        ++named;
        ++by_rule[rule].second;
      } else {
        verdict = about_other ? "WRONG" : "unattributed";
        wrong += about_other ? 1 : 0;
      }
    }
    std::cout << id << "\t" << verdict << "\t" << file << ":" << at << "\t" << rule << "\t" << what
              << "\n";
  }
  std::cout << "\nhalf " << half << ": " << counted << " mutants compile and lose points ("
            << not_compiling << " do not compile, " << not_losing << " lose none); named by the "
            << "first failure: " << named << " (" << (counted ? 100 * named / counted : 0)
            << " %), wrong: " << wrong << "\n";
  for (const auto& [rule, n] : by_rule)
    std::cout << "  " << rule << ": " << n.second << " of " << n.first << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 3 && args[0] == "generate") return generate(args[1], args[2]);
  if (args.size() == 4 && args[0] == "judge" && (args[3] == "A" || args[3] == "B"))
    return judge(args[1], args[2], args[3][0]);
  std::cerr << "usage: springlab-mutate generate KIT OUT | judge OUT RESULTS A|B\n";
  return 2;
}
