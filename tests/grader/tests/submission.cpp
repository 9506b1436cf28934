// Finding a submission's files in any of its three shapes, and the private copy that is compiled.
#include "submission.hpp"
#include "lab_catch.hpp"

#include <unistd.h>

#include <fstream>

using namespace springlab::grader;

namespace {

struct Folders {
  fs::path top =
      fs::temp_directory_path() / ("springlab-submission-test-" + std::to_string(getpid()));
  Kit kit;
  ~Folders() { fs::remove_all(top); }
  Folders(const Folders&) = delete;
  Folders& operator=(const Folders&) = delete;
  Folders() {
    fs::remove_all(top);
    kit.starter = top / "kit" / "tasks";
    kit.task_files = {
        {1, {"task1_two_masses/explicit_euler.cpp", "task1_two_masses/spring_damper.cpp"}},
        {2, {"task2_four_masses/spring_forces.cpp"}}};
    write(kit.starter / "task1_two_masses" / "explicit_euler.cpp", "starter euler");
    write(kit.starter / "task1_two_masses" / "spring_damper.cpp", "starter spring");
    write(kit.starter / "task2_four_masses" / "spring_forces.cpp", "starter forces");
  }
  static void write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }
  static std::string read(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

}  // namespace

TEST_CASE("The three shapes of a submission", "[submission]") {
  Folders f;
  f.write(f.top / "alice" / "task1_two_masses" / "spring_damper.cpp", "alice");
  f.write(f.top / "bob-repo" / "tasks" / "task2_four_masses" / "spring_forces.cpp", "bob");
  f.write(f.top / "carol" / "spring_forces.cpp", "carol");
  const Submission alice = find_submission(f.top / "alice", f.kit);
  CHECK(alice.name == "alice");
  CHECK(alice.layout == Layout::tasks_folder);
  CHECK(alice.tasks.at(1).found == std::vector<std::string>{"spring_damper.cpp"});
  CHECK(alice.tasks.at(1).missing == std::vector<std::string>{"explicit_euler.cpp"});
  const Submission bob = find_submission(f.top / "bob-repo", f.kit);
  CHECK(bob.layout == Layout::repository);
  CHECK(bob.tasks.at(2).found == std::vector<std::string>{"spring_forces.cpp"});
  const Submission carol = find_submission(f.top / "carol", f.kit);
  CHECK(carol.layout == Layout::loose_files);
  CHECK(carol.tasks.at(2).found == std::vector<std::string>{"spring_forces.cpp"});
  CHECK(carol.tasks.at(1).found.empty());
  CHECK_THROWS_AS(find_submission(f.top / "nobody", f.kit), UsageError);
}

TEST_CASE("The private copy: the task's files, the starter code for missing ones, no links",
          "[submission]") {
  Folders f;
  f.write(f.top / "alice" / "task1_two_masses" / "spring_damper.cpp", "alice's spring");
  f.write(f.top / "alice" / "task1_two_masses" / "helpers.hpp", "alice's helper");
  fs::create_symlink(f.kit.starter / "task1_two_masses" / "spring_damper.cpp",
                     f.top / "alice" / "task1_two_masses" / "linked.hpp");
  const Submission alice = find_submission(f.top / "alice", f.kit);
  const TaskCopy copy = copy_task(alice, 1, f.kit, f.top / "work");
  CHECK(copy.folder == f.top / "work" / "tasks" / "task1_two_masses");
  CHECK(f.read(copy.folder / "spring_damper.cpp") == "alice's spring");
  CHECK(f.read(copy.folder / "explicit_euler.cpp") == "starter euler");
  CHECK(f.read(copy.folder / "helpers.hpp") == "alice's helper");
  CHECK_FALSE(fs::exists(copy.folder / "linked.hpp"));
  REQUIRE(copy.notes.size() == 2);
  CHECK_THAT(copy.notes[0], lab_catch::Contains("linked.hpp is a link"));
  CHECK_THAT(copy.notes[1],
             lab_catch::Contains("explicit_euler.cpp is missing: graded as the starter"));
}

TEST_CASE("Copies have the same digest when their files are the same, and same_files tells",
          "[submission]") {
  Folders f;
  f.write(f.top / "a" / "spring_forces.cpp", "same");
  f.write(f.top / "b" / "task2_four_masses" / "spring_forces.cpp", "same");
  f.write(f.top / "c" / "spring_forces.cpp", "other");
  f.write(f.top / "d" / "spring_forces.cpp", "samE");
  const auto copy = [&](const std::string& name) {
    return copy_task(find_submission(f.top / name, f.kit), 2, f.kit, f.top / "work" / name);
  };
  const TaskCopy a = copy("a"), b = copy("b"), c = copy("c"), d = copy("d");
  CHECK(a.digest == b.digest);
  CHECK(a.digest != c.digest);
  CHECK(a.digest != d.digest);
  CHECK(same_files(a.folder, b.folder));
  CHECK_FALSE(same_files(a.folder, c.folder));
  CHECK_FALSE(same_files(a.folder, d.folder));
}

TEST_CASE("A task file larger than 1 MB is refused unread, and the copy says so", "[submission]") {
  Folders f;
  fs::create_directories(f.top / "big");
  {
    std::ofstream out(f.top / "big" / "spring_forces.cpp", std::ios::binary);
    out.seekp(std::streamoff(3 * largest_file));  // a sparse file: nothing is written
    out.put('x');
  }
  const TaskCopy copy =
      copy_task(find_submission(f.top / "big", f.kit), 2, f.kit, f.top / "work" / "big");
  CHECK_THAT(copy.problem,
             lab_catch::Contains("spring_forces.cpp is 3 MB: a task's file may have at "
                                 "most 1 MB"));
  CHECK_FALSE(fs::exists(copy.folder / "spring_forces.cpp"));
}

TEST_CASE("Linked folders are never followed, and a download's one wrapping folder is looked into",
          "[submission]") {
  Folders f;
  // A repository whose tasks/ is a link (to the kit's starter code here, or its solutions), and
  // a copy of tasks/ whose task 2 folder is.
  fs::create_directories(f.top / "linked");
  fs::create_directory_symlink(f.kit.starter, f.top / "linked" / "tasks");
  const Submission linked = find_submission(f.top / "linked", f.kit);
  CHECK(linked.empty());
  REQUIRE(linked.notes.size() == 1);
  CHECK_THAT(linked.notes[0], lab_catch::Contains("tasks/ is a link to a folder: left out"));
  f.write(f.top / "partly" / "task1_two_masses" / "spring_damper.cpp", "own");
  fs::create_directory_symlink(f.kit.starter / "task2_four_masses",
                               f.top / "partly" / "task2_four_masses");
  const Submission partly = find_submission(f.top / "partly", f.kit);
  CHECK(partly.tasks.at(1).found == std::vector<std::string>{"spring_damper.cpp"});
  CHECK(partly.tasks.at(2).found.empty());
  CHECK_THAT(partly.tasks.at(2).notes.at(0),
             lab_catch::Contains("task2_four_masses/ is a link to a folder: left out"));
  // GitHub's "Download ZIP": the repository inside a folder of its own.
  f.write(f.top / "zip" / "springlab-main" / "tasks" / "task2_four_masses" / "spring_forces.cpp",
          "zipped");
  const Submission zipped = find_submission(f.top / "zip", f.kit);
  CHECK(zipped.name == "zip");
  CHECK(zipped.layout == Layout::repository);
  CHECK(zipped.tasks.at(2).found == std::vector<std::string>{"spring_forces.cpp"});
  CHECK_THAT(zipped.notes.at(0), lab_catch::Contains("graded the files in springlab-main/"));
}
