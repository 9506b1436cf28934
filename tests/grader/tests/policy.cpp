// The source policy: what a submission may not write (inline assembler, attributes, pragmas,
// macros that tell the two builds apart), found wherever it hides in the text (line splices,
// macros) and never in comments or literals; named by file and line. And the premise that makes
// the policy on macros sufficient: both builds define the same macros.
#include "policy.hpp"
#include "kit.hpp"
#include "lab_catch.hpp"
#include "process.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

using namespace springlab::grader;

namespace {

struct Copy {
  fs::path folder = fs::temp_directory_path() / ("springlab-policy-" + std::to_string(getpid()));
  Copy() {
    fs::remove_all(folder);
    fs::create_directories(folder);
  }
  ~Copy() { fs::remove_all(folder); }
  Copy(const Copy&) = delete;
  Copy& operator=(const Copy&) = delete;
  std::optional<PolicyBreach> check(const std::string& text) const {
    std::ofstream(folder / "task.cpp") << text;
    return check_sources(folder, {"task.cpp"});
  }
};

}  // namespace

TEST_CASE("Inline assembler is refused however it is spelled, with its line", "[policy]") {
  const Copy c;
  for (const std::string& text :
       {std::string("int x;\nasm(\".incbin \\\"x\\\"\");\n"),
        std::string("int x;\n__asm__(\"\");\n"), std::string("int x;\n__asm volatile(\"nop\");\n"),
        std::string("int x;\nas\\\nm(\".fill 9\");\n")}) {
    const auto breach = c.check(text);
    INFO(text);
    REQUIRE(breach);
    CHECK(breach->line == 2);
    CHECK_THAT(breach->text(),
               lab_catch::StartsWith("task.cpp:2: inline assembler is not allowed"));
  }
}

TEST_CASE("Attributes of the compiler's own, pragmas and build-telling macros are refused",
          "[policy]") {
  const Copy c;
  struct Case {
    std::string text, named;
    int line = 2;  // after the comment that starts the file
  };
  const std::vector<Case> cases = {
      {"const char code[] __attribute__((section(\".text\"))) = {};", "__attribute__"},
      {"[[gnu::section(\".text\")]] const char code[] = {};", "[[gnu::...]]"},
      {"[[ gnu :: no_sanitize(\"address\") ]] void f();", "[[gnu::...]]"},
      {"[[using gnu: section(\".text\")]] const char code[] = {};", "[[using ...]]"},
      {"__declspec(noinline) void f();", "__declspec"},
      {"#pragma GCC optimize(\"O0\")", "#pragma GCC optimize(\"O0\")"},
      {"_Pragma(\"GCC optimize(2)\") int x;", "_Pragma"},
      {"#include_next <vector>", "#include_next"},
      {"#line 7 \"other.cpp\"", "#line"},
      {"%:embed \"x\"", "#embed"},
      {"#ifndef NDEBUG\n#endif", "NDEBUG"},
      {"#ifdef __SANITIZE_ADDRESS__\n#endif", "__SANITIZE_ADDRESS__"},
      {"#if __has_feature(address_sanitizer)\n#endif", "__has_feature"},
      {"extern \"C\" void __asan_poison_memory_region(void*, unsigned long);", "__asan_poison"},
      {"#if defined(__OPTIMIZE__)\n#endif", "__OPTIMIZE__"},
      {"#include <sys/mman.h>", "it includes sys/mman.h, which a submission may not"},
      {"#ifdef _WIN32\n#include <windows.h>\n#endif", "windows.h", 3},
      {"#include \"../../solutions/task1_two_masses/spring_damper.cpp\"", "../../solutions"},
      {"#include \"/proc/self/root/etc/shadow\"", "/proc/self/root"},
      {"#include <catch2/catch.hpp>", "Catch2"},
      {"#include \"springlab/../../solutions/task1_two_masses/spring_damper.cpp\"", "solutions"},
      {"#define HEADER <vector>\n#include HEADER", "not through a macro", 3}};
  for (const auto& [text, named, line] : cases) {
    INFO(text);
    const auto breach = c.check("// a comment\n" + text + "\n");
    REQUIRE(breach);
    CHECK(breach->line == line);
    CHECK_THAT(breach->what, lab_catch::Contains(named));
  }
}

TEST_CASE("What only looks like a breach is C++ a student may write", "[policy]") {
  const Copy c;
  const std::string text = R"cpp(#pragma once
#pragma GCC diagnostic ignored "-Wshadow"
#include <vector>
#include "springlab/task1_two_masses.hpp"
#include <Eigen/Core>
#include "helpers.hpp"
#include "math.h"
                                 // asm("nop"), __attribute__ and NDEBUG in a comment
                                 /* __asm__ in a block comment */
                                 const char* words = "asm __attribute__ NDEBUG";
                                 const char* raw = R"x(asm("nop") )" __attribute__ )x";
                                 const char quote = '"', letter = 'a';
                                 const long big = 1'000'000, hex = 0x1'FFu;
                                 const double e = 1.5e+3;
                                 int asm_count = 0, my_NDEBUG = 1;
                                 [[nodiscard]] int f();
                                 [[maybe_unused, deprecated("old")]] static int g() {
                                   return 0;
                                 }
                                 int h(int a[]) {
                                   return a[0] + [] { return 1; }();
                                 }
                                 const char* u = u8"\"asm";
  )cpp";
  const auto breach = c.check(text);
  CHECK_FALSE(breach);
  if (breach) FAIL(breach->text());
}

TEST_CASE("The preprocessor's output: what macros made of the copy's lines, and its includes",
          "[policy]") {
  IncludeRoots roots;
  roots.copy = "/work/copy";
  roots.kit_headers = "/kit/include";
  roots.standard = {"/usr/include/c++/12", "/usr/include"};
  roots.eigen = {"/usr/include/eigen3"};
  const auto check = [&](const std::string& text) {
    std::istringstream in(text);
    return check_preprocessed(in, roots);
  };
  const std::string start =
      "# 0 \"/work/copy/task.cpp\"\n# 0 \"<command-line>\"\n"
      "#pragma GCC pch_preprocess \"/pch/plain/pch.hpp.gch\"\n# 1 \"/work/copy/task.cpp\"\n";
  SECTION("a keyword made by a macro, on the copy's line") {
    const auto p = check(start + "int x;\n\n __asm__ (\".incbin \\\"/x\\\"\");\n");
    REQUIRE(p.breach);
    CHECK(p.breach->file == "task.cpp");
    CHECK(p.breach->line == 3);
    CHECK_THAT(p.breach->what, lab_catch::StartsWith("inline assembler") &&
                                   lab_catch::EndsWith("(written so through a macro)"));
  }
  SECTION("the system's own headers may use what the copy may not") {
    const auto p = check(start +
                         "# 1 \"/usr/include/c++/12/vector\" 1 3\n"
                         "extern int f() __attribute__ ((__nothrow__)) __asm__ (\"\" \"f64\");\n"
                         "# 2 \"/work/copy/task.cpp\" 2\nint y;\n");
    CHECK_FALSE(p.breach);
  }
  SECTION("allowed headers, and one that is not, named with the line that includes it") {
    const auto p = check(start +
                         "# 1 \"/usr/include/c++/12/vector\" 1 3\n# 2 \"/work/copy/task.cpp\" 2\n"
                         "# 1 \"/usr/include/eigen3/Eigen/Core\" 1\n# 3 \"/work/copy/task.cpp\" 2\n"
                         "# 1 \"/kit/include/springlab/types.hpp\" 1\n"
                         "# 1 \"/usr/include/x86_64-linux-gnu/sys/mman.h\" 1 3 4\n"
                         "# 2 \"/kit/include/springlab/types.hpp\" 2\n"
                         "# 4 \"/work/copy/task.cpp\" 2\n"
                         "# 1 \"/work/copy/helper.hpp\" 1\n# 5 \"/work/copy/task.cpp\" 2\n"
                         "\n# 1 \"/usr/include/dirent.h\" 1 3 4\n");
    REQUIRE(p.breach);
    CHECK(p.breach->file == "task.cpp");
    CHECK(p.breach->line == 6);
    CHECK_THAT(p.breach->what,
               lab_catch::StartsWith("it includes dirent.h, which a submission may not"));
    CHECK(p.own_files == std::vector<std::string>{"helper.hpp"});
  }
}

TEST_CASE("The standard library's headers are known by name", "[policy]") {
  for (const char* name : {"vector", "cmath", "math.h", "numbers", "bits/stdc++.h"})
    CHECK(is_standard_header(name));
  for (const char* name : {"unistd.h", "sys/mman.h", "dirent.h", "Eigen/Core", "dlfcn.h"})
    CHECK_FALSE(is_standard_header(name));
}

TEST_CASE("The plain and the sanitized build of submission code define the same macros",
          "[policy]") {
  const Kit kit = read_kit(SPRINGLAB_GRADER_KIT);
  const auto macros = [](std::vector<std::string> argv) {
    for (const char* arg : {"-dM", "-E", "-x", "c++", "/dev/null"})
      argv.push_back(arg);
    ProcessPool pool(1);
    Command c;
    c.argv = std::move(argv);
    c.env = plain_environment();
    c.directory = "/";
    c.limits.output_kept = c.limits.output_limit;
    std::string output;
    pool.add(std::move(c), [&](Outcome o) {
      CHECK(o.exited);
      CHECK(o.exit_code == 0);
      output = std::move(o.output);
    });
    pool.run();
    std::set<std::string> lines;  // the compiler lists them in no fixed order
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);)
      lines.insert(line);
    return lines;
  };
  const std::set<std::string> plain = macros(kit.plain.compile),
                              sanitized = macros(kit.sanitized.compile);
  CHECK(plain.size() > 1000);  // the standard library's and Eigen's too (the precompiled header)
  std::vector<std::string> differ;
  std::set_symmetric_difference(plain.begin(), plain.end(), sanitized.begin(), sanitized.end(),
                                std::back_inserter(differ));
  CHECK(differ.empty());
  for (const std::string& line : differ)
    WARN("in one build only: " << line);
  for (const std::string& line : plain)
    CHECK_THAT(line,
               !lab_catch::Contains("NDEBUG ") && !lab_catch::Contains("__SANITIZE_ADDRESS__"));
  CHECK(kit.plain.env == kit.sanitized.env);
}
