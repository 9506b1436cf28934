// What submission code may reach: the dependency files the compiler writes, the include rule
// and the symbol rule.
#include "checks.hpp"
#include "lab_catch.hpp"

#include <unistd.h>

#include <fstream>

using namespace springlab::grader;

namespace {

// A kit laid out as the real one, in a temporary folder.
struct FakeKit {
  fs::path top = fs::temp_directory_path() / ("springlab-checks-test-" + std::to_string(getpid()));
  Kit kit;
  fs::path copy = top / "work" / "tasks" / "task1_two_masses";
  ~FakeKit() { fs::remove_all(top); }
  FakeKit(const FakeKit&) = delete;
  FakeKit& operator=(const FakeKit&) = delete;
  FakeKit() {
    fs::remove_all(top);
    kit.root = top / "kit";
    kit.headers = kit.root / "common" / "include";
    kit.pch = top / "build" / "pch";
    kit.system_headers = {"/usr/include"};
    for (const fs::path& folder :
         {kit.headers / "springlab", kit.root / "solutions", copy, kit.pch})
      fs::create_directories(folder);
  }
};

}  // namespace

TEST_CASE("Dependency files: continued lines, escaped spaces and the target left out", "[checks]") {
  const fs::path file =
      fs::temp_directory_path() / ("springlab-deps-test-" + std::to_string(getpid()) + ".d");
  std::ofstream(file) << "/w/obj.o: /w/a.cpp /usr/include/x.h \\\n /w/my\\ header.hpp\n";
  const std::vector<fs::path> files = read_dependencies(file);
  REQUIRE(files.size() == 3);
  CHECK(files[0] == "/w/a.cpp");
  CHECK(files[2] == "/w/my header.hpp");
}

TEST_CASE("Includes: the submission's own files, the kit's headers and the system's only",
          "[checks]") {
  const FakeKit f;
  const Kit& kit = f.kit;
  CHECK(include_problem(f.copy / "spring_damper.cpp", f.copy, kit.pch, kit).empty());
  CHECK(include_problem(f.copy / "helpers.hpp", f.copy, kit.pch, kit).empty());
  CHECK(include_problem(kit.headers / "springlab" / "types.hpp", f.copy, kit.pch, kit).empty());
  CHECK(include_problem("/usr/include/c++/12/vector", f.copy, kit.pch, kit).empty());
  CHECK(include_problem(kit.pch / "pch.hpp", f.copy, kit.pch, kit).empty());
  // The solutions, however the path is spelt, and anything else of the kit.
  CHECK_THAT(
      include_problem(kit.root / "solutions" / "task1_two_masses" / "spring_damper.cpp", f.copy,
                      kit.pch, kit),
      lab_catch::Contains("solutions/task1_two_masses/spring_damper.cpp, a file of the kit"));
  CHECK_THAT(include_problem(kit.headers / "springlab" / ".." / ".." / ".." / "solutions" / "x.cpp",
                             f.copy, kit.pch, kit),
             lab_catch::Contains("solutions/x.cpp, a file of the kit"));
  CHECK_THAT(include_problem(f.copy / ".." / ".." / ".." / "kit" / "tests" / "a.cpp", f.copy,
                             kit.pch, kit),
             lab_catch::Contains("tests/a.cpp, a file of the kit"));
  CHECK_THAT(include_problem("/usr/include/catch2/catch.hpp", f.copy, kit.pch, kit),
             lab_catch::Contains("it includes Catch2"));
  CHECK_THAT(include_problem("/etc/passwd", f.copy, kit.pch, kit),
             lab_catch::Contains("/etc/passwd, which is outside your submission"));
}

TEST_CASE("Symbols: main, Catch2, the kit's own code and loading code are each named once",
          "[checks]") {
  CHECK(symbol_problems(
            "a.o: "
            "_ZN9springlab10submission12spring_forceERKN5Eigen6MatrixIdLi2ELi1ELi0ELi2ELi1EEES5_dd "
            "T 0 10\n"
            "a.o: "
            "_ZN9springlab16velocity_settledERKN5Eigen6MatrixIdLi2ELin1ELi0ELi2ELin1EEES4_S4_d U\n"
            "a.o: malloc U\n")
            .empty());
  const std::vector<std::string> problems = symbol_problems(
      "a.o: main T 0 10\n"
      "a.o: "
      "_ZN5Catch7AutoRegC1ERKNS_9ITestInvokerERKNS_14SourceLineInfoERKNS_9StringRefERKNS_"
      "10NameAndTagsE U\n"
      "b.o: _ZN5Catch7AutoRegD1Ev U\n"
      "b.o: _ZN9springlab9reference12spring_forceERKN5Eigen6MatrixIdLi2ELi1ELi0ELi2ELi1EEES5_dd U\n"
      "b.o: dlsym U\n");
  REQUIRE(problems.size() == 4);
  CHECK_THAT(problems[0], lab_catch::Contains("defines main()"));
  CHECK_THAT(problems[1], lab_catch::Contains("uses Catch2"));
  CHECK_THAT(problems[2], lab_catch::Contains("calls springlab::reference::spring_force"));
  CHECK_THAT(problems[3], lab_catch::Contains("loads code at run time (dlsym)"));
}

TEST_CASE("Review notes: calls no task needs, each kind named once with what was called",
          "[checks]") {
  CHECK(review_notes("a.o: sqrt U\na.o: _Znwm U\n").empty());
  const std::vector<std::string> notes = review_notes(
      "a.o: _exit U\n"
      "a.o: fopen U\n"
      "b.o: fopen U\n"
      "b.o: _ZNSt14basic_ofstreamIcSt11char_traitsIcEEC1EPKcSt13_Ios_Openmode U\n"
      "b.o: syscall U\n"
      "b.o: exit T 0 4\n");
  REQUIRE(notes.size() == 4);
  CHECK(notes[0] == "ends the program (_exit)");
  CHECK(notes[1] == "uses files (fopen)");
  CHECK(notes[2] == "uses files (std::basic_ofstream...)");
  CHECK(notes[3] == "reaches memory or the system directly (syscall)");
}
