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

TEST_CASE("Characters a source has no business holding are refused, with their line", "[policy]") {
  const Copy c;
  struct Case {
    std::string text, named;
    int line = 2;
  };
  using namespace std::string_literals;
  const std::vector<Case> cases = {
      {"int a;\n#\0line 1 \"/usr/include/stdlib.h\"\n"s, "a NUL byte (0x00)"},
      {"int a;\n#\v1 \"/usr/include/stdlib.h\" 3\n", "a control character (0x0B)"},
      {"int a;\nint b; \x1b[2J\n", "a control character (0x1B)"},
      {"int a;\nint b; \x7f\n", "a control character (0x7F)"},
      {"int a;\nint b;\r# 1 \"/usr/include/stdlib.h\" 3\r\n",
       "a carriage return that does not end"},
      {"int a;\nint b;\r", "a carriage return that does not end"}};
  for (const auto& [text, named, line] : cases) {
    INFO(text);
    const auto breach = c.check(text);
    REQUIRE(breach);
    CHECK(breach->line == line);
    CHECK_THAT(breach->what, lab_catch::Contains(named));
  }
  // Ordinary text: CRLF line ends, tabs, form feeds, UTF-8 and an older encoding in comments.
  for (const std::string& text :
       {std::string("int a;\r\n\tint b;\r\n"), std::string("int a;\f\nint b;\n"),
        std::string("// Kraft in Newton, \xc3\xa9t\xc3\xa9\nint a;\n"),
        std::string("// \xe9t\xe9 (Latin-1)\nint a;\n")}) {
    const auto breach = c.check(text);
    CHECK_FALSE(breach);
    if (breach) FAIL(breach->text());
  }
}

TEST_CASE("A leading byte-order mark is dropped first, never ignored", "[policy]") {
  const Copy c;
  const std::string mark = "\xEF\xBB\xBF";
  CHECK_FALSE(c.check(mark + "#include <vector>\nint a;\n"));
  for (const std::string& first :
       {std::string("# 1 \"/usr/include/stdlib.h\" 3"),
        std::string("#line 1 \"/usr/include/stdlib.h\""), std::string("asm(\"nop\");")}) {
    INFO(first);
    const auto breach = c.check(mark + first + "\nint a;\n");
    REQUIRE(breach);
    CHECK(breach->line == 1);
  }
  // A second mark is a character like any other (and not a C++ one): never a blank.
  CHECK_FALSE(c.check("int a;\n" + mark + "\n"));
}

TEST_CASE("Line markers are refused wherever GCC reads a directive", "[policy]") {
  const Copy c;
  struct Case {
    std::string text;
    int line = 2;
  };
  const std::vector<Case> cases = {
      {"#line 7 \"other.cpp\""},
      {"#line 7"},
      {"# 1 \"/usr/include/stdlib.h\" 3"},
      {"#\f1 \"/usr/include/stdlib.h\" 3"},      // GCC reads a form feed as a blank
      {"# /* a comment */ 12 \"x.h\""},          // and a comment
      {"#\\\f\n1 \"/usr/include/stdlib.h\" 3"},  // and joins lines with blanks after the backslash
      {"#\\ \t\n line 4"},
      {"%:line 3"}};
  for (const auto& [text, line] : cases) {
    INFO(text);
    const auto breach = c.check("int a;\n" + text + "\nint b;\n");
    REQUIRE(breach);
    CHECK(breach->line == line);
    CHECK_THAT(breach->what, lab_catch::StartsWith("a line marker (#line, or # and a number)"));
  }
  const auto asks = c.check("int a;\n#if __has_include(<unistd.h>)\n#endif\n");
  REQUIRE(asks);
  CHECK(asks->line == 2);
  CHECK_THAT(asks->what, lab_catch::StartsWith("__has_include is not allowed"));
}

TEST_CASE("The build's preprocessing: a line marker the preprocessor did not make is refused",
          "[policy]") {
  IncludeRoots roots;
  roots.copy = "/work/copy";
  roots.kit_headers = "/kit/include";
  roots.standard = {"/usr/include/c++/12", "/usr/include"};
  const auto check = [&](const std::string& text) {
    std::istringstream in(
        "# 0 \"/work/copy/task.cpp\"\n# 1 \"/work/build//\"\n# 0 \"<built-in>\"\n"
        "# 0 \"<command-line>\"\n#pragma GCC pch_preprocess \"/pch/plain/pch.hpp.gch\"\n"
        "# 1 \"/work/copy/task.cpp\"\n" +
        text);
    return check_preprocessed(in, roots);
  };
  // The preprocessor's own: entering and leaving a header, and skipping blank lines; and what a
  // system header says of itself, its business.
  CHECK_FALSE(check("# 1 \"/usr/include/c++/12/vector\" 1 3\nint v;\n"
                    "# 9 \"/usr/include/c++/12/vector.tcc\" 3\nint w;\n"
                    "# 2 \"/work/copy/task.cpp\" 2\nint a;\n# 40 \"/work/copy/task.cpp\"\nint b;\n")
                  .breach);
  for (const std::string& forged :
       {std::string("# 1 \"/usr/include/stdlib.h\" 3\n"), std::string("# 1 \"<built-in>\"\n"),
        std::string("# 7 \"/work/copy/task.cpp\" 2\n")}) {
    INFO(forged);
    const auto p = check("int a;\nint b;\n" + forged + "__asm__(\"nop\");\n");
    REQUIRE(p.breach);
    CHECK(p.breach->file == "task.cpp");
    CHECK(p.breach->line == 3);
    CHECK_THAT(p.breach->what, lab_catch::StartsWith("a line marker"));
  }
}

namespace {

// The policy's own reading of one file, as the grader makes it (without the sandbox: the check
// of its output is what is tested here).
struct OwnReading {
  const Kit kit = read_kit(SPRINGLAB_GRADER_KIT);
  fs::path folder = fs::temp_directory_path() / ("springlab-stand-ins-" + std::to_string(getpid()));
  StandIns stand_ins = prepare_stand_ins(kit, folder / "stand-ins");
  fs::path copy = folder / "copy";
  OwnReading() { fs::create_directories(copy); }
  ~OwnReading() { fs::remove_all(folder); }
  OwnReading(const OwnReading&) = delete;
  OwnReading& operator=(const OwnReading&) = delete;

  Preprocessed check(const std::string& text) const {
    std::ofstream(copy / "task.cpp", std::ios::binary | std::ios::trunc) << text;
    std::vector<std::string> argv = stand_in_flags(kit.plain.compile, stand_ins);
    for (const std::string& arg :
         {std::string("-include"), stand_ins.macros.string(), std::string("-E"),
          (copy / "task.cpp").string(), std::string("-o"), (folder / "task.ii").string()})
      argv.push_back(arg);
    ProcessPool pool(1);
    Command c;
    c.argv = std::move(argv);
    c.env = plain_environment();
    c.directory = folder.string();
    c.limits.file_size_mb = 32;
    pool.add(std::move(c), [](Outcome o) {
      INFO(o.output);
      CHECK(o.exited);
      CHECK(o.exit_code == 0);
    });
    pool.run();
    std::ifstream in(folder / "task.ii");
    return check_stand_in_output(in, copy, stand_ins);
  }
};

}  // namespace

TEST_CASE("The compiler's own reading against stand-ins: all of it checked, its markers its own",
          "[policy]") {
  const OwnReading reading;
  const std::string join = "#define JOIN(a, b) a##b\n";
  const std::string hidden = "JOIN(__as, m__)(\"nop\");\n";
  SECTION("a line marker is refused, whatever bytes would hide it from a lexer") {
    using namespace std::string_literals;
    for (const std::string& marker :
         {"#\f1 \"/usr/include/stdlib.h\" 3\n"s, "#\\\f\n1 \"/usr/include/stdlib.h\" 3\n"s,
          "#\0line 1 \"/usr/include/stdlib.h\"\n"s, "#\v 1 \"/usr/include/stdlib.h\" 3\n"s,
          "# 1 \"/usr/include/stdlib.h\" 1 3\n"s, "#line 100000\n"s, "#line 3 \"other.cpp\"\n"s}) {
      INFO(marker);
      const Preprocessed p = reading.check(join + "int a;\n" + marker + hidden);
      REQUIRE(p.breach);
      CHECK(p.breach->file == "task.cpp");
      CHECK_THAT(p.breach->what, lab_catch::StartsWith("a line marker"));
    }
    const Preprocessed p = reading.check("\xEF\xBB\xBF# 1 \"/usr/include/stdlib.h\" 3\n" + hidden);
    REQUIRE(p.breach);
    CHECK_THAT(p.breach->what, lab_catch::StartsWith("a line marker"));
  }
  SECTION("what the copy's macros and the library's make is checked, on its line") {
    const Preprocessed own = reading.check(join + "int a;\n" + hidden);
    REQUIRE(own.breach);
    CHECK(own.breach->line == 3);
    CHECK_THAT(own.breach->what, lab_catch::StartsWith("inline assembler is not allowed"));
    const Preprocessed library = reading.check("#include <cstdio>\n__CONCAT(__as, m__)(\"\");\n");
    REQUIRE(library.breach);
    CHECK(library.breach->line == 2);
    // #if goes as in the build: the precompiled header's macros are there.
    const Preprocessed branch =
        reading.check(join + "#ifdef _GLIBCXX_VECTOR\n" + hidden + "#endif\n");
    REQUIRE(branch.breach);
    CHECK(branch.breach->line == 3);
  }
  SECTION("C++ a student may write passes, and the copy's headers it reads are named") {
    std::ofstream(reading.copy / "helper.hpp") << "#pragma once\ninline int twice(int x) {\n"
                                                  "  return 2 * x;\n}\n";
    const Preprocessed p = reading.check(
        "#include <vector>\n#include <cmath>\n#include <Eigen/Core>\n"
        "#include \"springlab/task1_two_masses.hpp\"\n#include \"helper.hpp\"\n"
        "#pragma GCC diagnostic push\n" +
        std::string(20, '\n') + "const char* raw = R\"x(\nasm\n)x\";\n#define N 3\nint a = N;\n" +
        "double pi = M_PI;\n#pragma GCC diagnostic pop\n");
    CHECK_FALSE(p.breach);
    if (p.breach) FAIL(p.breach->text());
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
