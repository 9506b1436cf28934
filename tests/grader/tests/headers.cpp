// Correct code links (issue 37): every function declared in the headers a task file includes
// (its task header and every kit header that brings in, common/include/springlab/) is defined in
// what the grader links a submission library from (kit.toml's [library]: the other tasks'
// forwarders, the table, and the task support library), or is the task's own, which the
// submission defines. A task 5 that called WindField::velocities, documented in wind.hpp, did not
// link under the grader: wind_velocities.cpp was in the core library only.
#include "cpp_lexer.hpp"
#include "kit.hpp"
#include "lab_catch.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace springlab::grader;

namespace {

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The kit headers `header` includes ("springlab/wind.hpp" as "wind.hpp").
std::vector<std::string> kit_includes(const fs::path& header) {
  std::vector<std::string> found;
  Lexer lexer(read(header));
  for (Token t; lexer.next(t);) {
    if (t.kind != Token::directive || t.text != "include") continue;
    const std::string operand = lexer.rest_of_line();
    const std::string prefix = "\"springlab/";
    const auto from = operand.find(prefix), to = operand.rfind('"');
    if (from != std::string::npos && to > from + prefix.size())
      found.push_back(operand.substr(from + prefix.size(), to - from - prefix.size()));
  }
  return found;
}

// One scope of a header: a namespace (the file's too) or a class, whose declarations count, or
// anything else (a function's body, an enum, an initialiser), whose contents do not.
struct Scope {
  enum Kind { names, type, other } kind = names;
  std::string name;  // "springlab::" for a namespace, "springlab::WindField::" for a class
};

bool is_one_of(const std::string& text, std::initializer_list<const char*> words) {
  for (const char* word : words)
    if (text == word) return true;
  return false;
}

// The name of the function a statement at namespace or class scope declares without defining
// ("operator" for an operator), or nothing: not inline, constexpr, a template, deleted, defaulted
// or pure, and not a variable or a function pointer.
std::optional<std::string> declared_name(const std::vector<Token>& s) {
  if (s.empty() || is_one_of(s.front().text, {"using", "typedef", "friend", "static_assert",
                                              "template", "namespace"}))
    return std::nullopt;
  int depth = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::string& t = s[i].text;
    if (s[i].kind == Token::identifier && is_one_of(t, {"inline", "constexpr", "consteval"}))
      return std::nullopt;  // defined in the header, no symbol needed
    if (depth == 0 && t == "=")
      return std::nullopt;  // a variable's initialiser (or = default, = delete)
    if (t == "(" && depth == 0) {
      if (i == 0 || s[i - 1].kind != Token::identifier)
        return std::nullopt;  // a function pointer, say
      // `= 0`, `= default` or `= delete` after the parameters: nothing to link
      for (std::size_t j = i; j < s.size(); ++j)
        if (s[j].text == "=") return std::nullopt;
      const std::string name = s[i - 1].text;
      return name == "operator" ? "operator" : name;
    }
    if (t == "(" || t == "[") ++depth;
    if (t == ")" || t == "]") --depth;
  }
  return std::nullopt;
}

// The scope a '{' after `statement` opens inside `outer`: a namespace's or a class's names, or
// another (a function's body, an initialiser).
Scope scope_opened(const std::vector<Token>& statement, const Scope& outer) {
  Scope inner{Scope::other, ""};
  if (!statement.empty() && statement.front().text == "namespace") {
    inner = {Scope::names, outer.name};
    for (const Token& word : statement)
      if (word.kind == Token::identifier && word.text != "namespace" && word.text != "inline")
        inner.name += word.text + "::";
  } else if (!statement.empty() &&
             is_one_of(statement.front().text, {"class", "struct", "union"}) &&
             statement.size() >= 2 && statement[1].kind == Token::identifier) {
    inner = {Scope::type, outer.name + statement[1].text + "::"};
  }
  return inner;
}

// The functions a header declares without defining, as "springlab::WindField::velocities":
// declarations at namespace or class scope that end in ';', have a parameter list and are not
// inline, constexpr, templates, deleted, defaulted or pure. The kit's headers are plain enough for
// this: no macros but the task API's brackets, which open and close namespaces.
std::set<std::string> declared_functions(const fs::path& header) {
  std::set<std::string> found;
  std::vector<Scope> scopes{{Scope::names, ""}};
  std::vector<Token> statement;
  int line_of_directive = -1;
  for (const Token& t : tokens(read(header))) {
    if (t.kind == Token::directive) {
      line_of_directive = t.line;
      continue;
    }
    if (t.line == line_of_directive) continue;  // a directive's operands
    // The task API's brackets: namespace springlab (and the build's inline namespace, which
    // plain_name drops), opened and closed.
    if (t.kind == Token::identifier && t.text == "SPRINGLAB_TASK_API_BEGIN") {
      scopes.push_back({Scope::names, scopes.back().name + "springlab::"});
      continue;
    }
    if (t.kind == Token::identifier && t.text == "SPRINGLAB_TASK_API_END") {
      scopes.pop_back();
      continue;
    }
    if (scopes.back().kind == Scope::other) {
      if (t.text == "{") scopes.push_back({Scope::other, ""});
      if (t.text == "}") scopes.pop_back();
      continue;
    }
    if (t.text == ":" && statement.size() == 1 &&
        is_one_of(statement.front().text, {"public", "private", "protected"})) {
      statement.clear();
      continue;
    }
    if (t.text == ";") {
      if (const auto name = declared_name(statement)) found.insert(scopes.back().name + *name);
      statement.clear();
    } else if (t.text == "{") {
      scopes.push_back(scope_opened(statement, scopes.back()));
      statement.clear();
    } else if (t.text == "}") {
      scopes.pop_back();
      statement.clear();
    } else {
      statement.push_back(t);
    }
  }
  return found;
}

// "springlab::submission::WindField::velocities(double, ...) const" as
// "springlab::WindField::velocities": the build's inline namespace and the parameters dropped.
std::string plain_name(std::string name) {
  const std::string inline_namespace = "submission::";
  if (const auto at = name.find(inline_namespace); at != std::string::npos)
    name.erase(at, inline_namespace.size());
  int depth = 0;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '<') ++depth;
    if (name[i] == '>') --depth;
    if (name[i] == '(' && depth == 0) return name.substr(0, i);
  }
  return name;
}

// Every function defined, visible to a linker, in `parts` (objects and archives), by plain_name.
std::set<std::string> defined_functions(const fs::path& nm, const std::vector<fs::path>& parts) {
  std::string command = nm.string() + " -C -P --defined-only --extern-only";
  for (const fs::path& part : parts)
    command += " '" + part.string() + "'";
  command += " 2>/dev/null";
  std::set<std::string> found;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string output;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    output.append(buffer, n);
  REQUIRE(::pclose(pipe) == 0);
  // "NAME TYPE VALUE [SIZE]", NAME with spaces of its own once demangled; code only (T, W and
  // i: a text, weak or load-time-chosen function).
  const std::regex function(R"(^(.+) [TWi] [0-9a-f]+( [0-9a-f]+)?$)");
  std::istringstream lines(output);
  std::smatch m;
  for (std::string line; std::getline(lines, line);)
    if (std::regex_match(line, m, function)) found.insert(plain_name(m[1].str()));
  return found;
}

// What parameters.hpp declares for the kit's scene files and front ends (checking and setting
// scene parameters by name): the scenes library's, which no task needs and a submission does not
// link with. Listed here so that any other function a task's headers declare must be linkable,
// and checked below to be exactly what is missing, so that the list cannot go stale.
const std::set<std::string> scene_file_functions = {
    "springlab::Range::contains", "springlab::Range::describe", "springlab::validate",
    "springlab::validate_built",  "springlab::set_parameter",   "springlab::set_number",
    "springlab::set_assignment",  "springlab::nearest_key",     "springlab::is_parameter_table",
    "springlab::unknown_key"};

}  // namespace

TEST_CASE("Every function a task's headers declare is in what a submission links against",
          "[headers]") {
  const Kit kit = read_kit(SPRINGLAB_GRADER_KIT);
  const fs::path headers = kit.headers / "springlab";
  for (const auto& [task, files] : kit.task_files) {
    // The task's header (tasks/task5_fabric/ has springlab/task5_fabric.hpp) and every kit header
    // it brings in.
    const std::string task_header = kit.task_folder(task) + ".hpp";
    std::set<std::string> reached{task_header};
    std::vector<std::string> pending{task_header};
    while (!pending.empty()) {
      const std::string next = pending.back();
      pending.pop_back();
      for (const std::string& included : kit_includes(headers / next))
        if (reached.insert(included).second) pending.push_back(included);
    }
    const std::set<std::string> own = declared_functions(headers / task_header);
    const std::set<std::string> defined = defined_functions(kit.nm, kit.library_parts.at(task));
    std::set<std::string> missing;
    for (const std::string& header : reached) {
      if (header == task_header) continue;
      for (const std::string& function : declared_functions(headers / header))
        if (own.count(function) == 0 && defined.count(function) == 0) {
          missing.insert(function);
          INFO("task " << task << ": " << function << ", declared in springlab/" << header
                       << ", is not in what a submission links against");
          CHECK(scene_file_functions.count(function) > 0);
        }
    }
    if (reached.count("parameters.hpp") > 0) CHECK(missing == scene_file_functions);
    // The other tasks' functions, which a task may call, are the library's too.
    for (const auto& [other, other_files] : kit.task_files) {
      if (other == task) continue;
      for (const std::string& function :
           declared_functions(headers / (kit.task_folder(other) + ".hpp"))) {
        INFO("task " << task << ": task " << other << "'s " << function);
        CHECK(defined.count(function) > 0);
      }
    }
    // The walk found what it must: the task's own functions, and the wind's for task 5.
    CHECK_FALSE(own.empty());
    if (task == 5) CHECK(reached.count("wind.hpp") > 0);
  }
}
