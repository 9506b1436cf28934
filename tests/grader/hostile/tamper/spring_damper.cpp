// Attack: correct task 1 physics, but the first call of spring_force also tries to copy the kit's
// task 5 solutions over this submission's own task 5 files (left as the starter stubs), so that
// task 5 would be graded as the reference. It finds everything at run time: the kit from the
// test program's path (/proc/self/exe, searching upwards for solutions/task5_fabric), the private
// copy of this submission from __FILE__ (its sibling task5_fabric/), and the submission itself by
// searching near the working folder for a "tamper" folder with task 5 files. Every failure is
// caught: the sandbox must refuse every write (task 5 stays the stubs: no points), and task 1 is
// then graded on its physics (full marks).
#include "springlab/task1_two_masses.hpp"

#include <filesystem>
#include <string>
#include <vector>

using namespace springlab;
namespace fs = std::filesystem;

namespace {

fs::path find_kit_task5() {
  std::error_code error;
  fs::path at = fs::read_symlink("/proc/self/exe", error).parent_path();
  for (; !at.empty() && at != at.root_path(); at = at.parent_path())
    if (fs::is_regular_file(at / "solutions/task5_fabric/pins.cpp", error))
      return at / "solutions/task5_fabric";
  return {};
}

std::vector<fs::path> find_targets() {
  std::vector<fs::path> targets;
  std::error_code error;
  // The private copy the grader compiled: this file's own folder's sibling.
  targets.push_back(fs::path(__FILE__).parent_path().parent_path() / "task5_fabric");
  // The submission as handed in: a folder named "tamper" near the working folder.
  fs::path start = fs::current_path(error);
  int visited = 0;
  for (int up = 0; up < 4 && start.has_parent_path() && start != start.root_path(); ++up) {
    start = start.parent_path();
    fs::recursive_directory_iterator it(start, fs::directory_options::skip_permission_denied,
                                        error), end;
    for (; !error && it != end && visited < 20000; it.increment(error), ++visited) {
      if (it.depth() > 4) it.disable_recursion_pending();
      const fs::path& p = it->path();
      if (p.filename() == "task5_fabric" &&
          (p.parent_path().filename() == "tamper" ||
           p.parent_path().parent_path().filename() == "tamper"))
        targets.push_back(p);
    }
  }
  return targets;
}

int tamper_once() {
  int copied = 0;
  try {
    const fs::path kit = find_kit_task5();
    if (kit.empty()) return 0;
    for (const fs::path& target : find_targets())
      for (const char* file : {"bend_springs.cpp", "external_forces.cpp", "pins.cpp"}) {
        std::error_code error;
        if (fs::copy_file(kit / file, target / file, fs::copy_options::overwrite_existing, error))
          ++copied;
      }
  } catch (...) {
  }
  return copied;
}

}  // namespace

Vec2 springlab::spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length) {
  static const int copied = tamper_once();
  (void)copied;
  const Vec2 d = r_p - r_q;
  const double length = d.norm();
  if (length == 0.0) return Vec2::Zero();
  return -k * (length - rest_length) * d / length;
}

Vec2 springlab::damper_force(const Vec2& v_p, const Vec2& v_q, double b) {
  return -b * (v_p - v_q);
}
