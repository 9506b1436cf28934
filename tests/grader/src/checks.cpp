#include "checks.hpp"

#include "policy.hpp"

#include <cxxabi.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

namespace springlab::grader {
namespace {

fs::path canonical_or_same(const fs::path& path) {
  std::error_code error;
  fs::path result = fs::weakly_canonical(path, error);
  return error ? path.lexically_normal() : result;
}

std::string demangle(const std::string& symbol) {
  int status = 0;
  const std::unique_ptr<char, decltype(&std::free)> text(
      abi::__cxa_demangle(symbol.c_str(), nullptr, nullptr, &status), &std::free);
  return status == 0 && text ? std::string(text.get()) : symbol;
}

}  // namespace

std::vector<fs::path> read_dependencies(const fs::path& dependency_file) {
  std::ifstream in(dependency_file);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::vector<std::string> tokens(1);
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\\' && i + 1 < text.size() && text[i + 1] == '\n') {
      ++i;  // a continued line
      if (!tokens.back().empty()) tokens.emplace_back();
    } else if (c == '\\' && i + 1 < text.size() && (text[i + 1] == ' ' || text[i + 1] == '#')) {
      tokens.back() += text[++i];
    } else if (c == '$' && i + 1 < text.size() && text[i + 1] == '$') {
      tokens.back() += text[++i];
    } else if (c == ' ' || c == '\t' || c == '\n') {
      if (!tokens.back().empty()) tokens.emplace_back();
    } else {
      tokens.back() += c;
    }
  }
  std::vector<fs::path> files;
  bool after_target = false;
  for (const std::string& token : tokens) {
    if (token.empty()) continue;
    if (!after_target) {
      after_target = token.back() == ':';
      continue;
    }
    files.emplace_back(token);
  }
  return files;
}

std::string include_problem(const fs::path& file, const fs::path& copy, const fs::path& pch,
                            const Kit& kit) {
  const fs::path f = canonical_or_same(file);
  if (is_within(f, canonical_or_same(copy)) || is_within(f, canonical_or_same(pch)) ||
      is_within(f, canonical_or_same(kit.headers)))
    return "";
  const fs::path root = canonical_or_same(kit.root);
  if (is_within(f, root))
    return "it includes " + f.lexically_relative(root).string() +
           ", a file of the kit: submission code may include only the kit's headers "
           "(common/include/springlab/...) and its own files";
  if (std::find(f.begin(), f.end(), fs::path("catch2")) != f.end())
    return "it includes Catch2 (" + f.string() +
           "): a submission holds the task's functions, never tests of its own";
  for (const fs::path& system : kit.system_headers)
    if (is_within(f, canonical_or_same(system))) return "";
  return "it includes " + f.string() +
         ", which is outside your submission: include only the kit's headers, the standard "
         "library's, Eigen's and your own files";
}

// The symbols an object file refers to but does not define, demangled.
std::vector<std::string> undefined_symbols(const std::string& nm_output) {
  std::vector<std::string> names;
  std::istringstream lines(nm_output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string file, symbol, type;
    if (fields >> file >> symbol >> type && (type == "U" || type == "w"))
      names.push_back(demangle(symbol));
  }
  return names;
}

std::vector<std::string> review_notes(const std::string& nm_output) {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> kinds = {
      {"ends the program", {"exit", "_exit", "_Exit", "quick_exit", "abort"}},
      {"starts programs",
       {"system", "popen", "fork", "vfork", "execv", "execve", "execvp", "execl", "execlp",
        "posix_spawn", "posix_spawnp"}},
      {"starts threads", {"pthread_create", "std::thread::_M_start_thread"}},
      {"uses files",
       {"fopen", "fopen64", "open", "open64", "openat", "creat", "std::basic_ofstream",
        "std::basic_ifstream", "std::basic_fstream", "std::filesystem::"}},
      {"handles or sends signals", {"signal", "sigaction", "raise", "kill"}},
      {"reaches memory or the system directly",
       {"syscall", "mmap", "mmap64", "mprotect", "ptrace", "process_vm_readv"}},
      {"reads the environment", {"getenv", "secure_getenv"}},
      {"sleeps", {"sleep", "usleep", "nanosleep", "clock_nanosleep"}},
      {"jumps out of functions", {"setjmp", "_setjmp", "longjmp", "siglongjmp"}}};
  std::vector<std::string> notes;
  for (const std::string& name : undefined_symbols(nm_output))
    for (const auto& [kind, prefixes] : kinds)
      for (const std::string& prefix : prefixes) {
        const bool whole = prefix.find("::") == std::string::npos;
        const bool match =
            whole ? name == prefix || name.rfind(prefix + "@", 0) == 0 : name.rfind(prefix, 0) == 0;
        const std::string note = kind + " (" + (whole ? name : prefix + "...") + ")";
        if (match && std::find(notes.begin(), notes.end(), note) == notes.end())
          notes.push_back(note);
      }
  return notes;
}

std::vector<std::string> symbol_problems(const std::string& nm_output) {
  std::vector<std::string> problems;
  const auto add = [&](const std::string& problem) {
    if (std::find(problems.begin(), problems.end(), problem) == problems.end())
      problems.push_back(problem);
  };
  std::istringstream lines(nm_output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string file, symbol, type;
    if (!(fields >> file >> symbol >> type)) continue;
    const bool defined = type != "U" && type != "w" && type != "v";
    const bool global = !type.empty() && (std::isupper(static_cast<unsigned char>(type[0])) ||
                                          type == "i" || type == "u");
    const std::string name = demangle(symbol);
    // Names the system and the compiler reserve (extern "C" __gmon_start__, say, would be called
    // while the library loads, before the test process is restricted), and functions chosen at
    // load time (ifunc resolvers run then too): C++ code never defines either by itself.
    const bool reserved = symbol.rfind("_Z", 0) != 0 && symbol.size() > 1 && symbol[0] == '_' &&
                          (symbol[1] == '_' || std::isupper(static_cast<unsigned char>(symbol[1])));
    if (defined && (type == "i" || (global && reserved))) {
      add("it defines " + symbol.substr(0, 80) +
          (type == "i" ? ", a function chosen while the library loads"
                       : ", a name reserved for the system and the compiler") +
          ": a submission defines its task's functions and helpers of its own");
      continue;
    }
    if (defined && (name == "main" || name.rfind("main(", 0) == 0))
      add("it defines main(): a submission holds the task's functions; the kit has the program");
    else if (name.find("Catch::") != std::string::npos)
      add("it uses Catch2 (" + name.substr(0, 80) +
          "): a submission holds the task's functions, never tests of its own");
    else if (!defined && (name.rfind("springlab::reference::", 0) == 0 ||
                          name.rfind("springlab::student_task", 0) == 0 ||
                          name.rfind("springlab::graded::", 0) == 0 ||
                          name.rfind("springlab::grading::", 0) == 0))
      add("it calls " + name.substr(0, name.find('(')) +
          ", which belongs to the kit's own code: write the function yourself");
    else if (!defined &&
             (name == "dlopen" || name == "dlsym" || name == "dlmopen" || name == "dlvsym"))
      add("it loads code at run time (" + name + "): a submission runs only its own code");
  }
  return problems;
}

}  // namespace springlab::grader
