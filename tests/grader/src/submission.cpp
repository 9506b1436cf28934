#include "submission.hpp"

#include "reports.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace springlab::grader {
namespace {

constexpr std::uintmax_t largest_file = 1 << 20;  // bytes: larger files are left out
constexpr int most_files = 64;                    // files copied per task folder

std::string file_name(const std::string& kit_path) {
  return kit_path.substr(kit_path.find('/') + 1);
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

std::string to_string(Layout layout) {
  switch (layout) {
    case Layout::tasks_folder:
      return "a copy of tasks/";
    case Layout::repository:
      return "a student repository";
    case Layout::loose_files:
      return "loose files";
  }
  return "?";
}

bool Submission::empty() const {
  for (const auto& [task, source] : tasks)
    if (!source.found.empty()) return false;
  return true;
}

namespace {

// A folder of the submission's own, not a link to one.
bool real_folder(const fs::path& path) {
  return fs::is_directory(fs::symlink_status(path));
}

bool holds_tasks(const fs::path& folder, const Kit& kit) {
  if (real_folder(folder / "tasks")) return true;
  for (const auto& [task, files] : kit.task_files) {
    if (real_folder(folder / kit.task_folder(task))) return true;
    for (const std::string& file : files)
      if (fs::is_regular_file(fs::symlink_status(folder / file_name(file)))) return true;
  }
  return false;
}

}  // namespace

Submission find_submission(const fs::path& folder, const Kit& kit) {
  std::error_code error;
  fs::path root = fs::canonical(folder, error);
  if (error || !fs::is_directory(root))
    throw UsageError("submission '" + printable(folder.string()) + "': not a folder");
  Submission s;
  s.folder = root;
  s.name = root.filename().string();
  if (s.name.empty()) s.name = "root";
  if (!holds_tasks(root, kit)) {
    std::vector<fs::path> inside;
    for (const fs::directory_entry& entry : fs::directory_iterator(root, error))
      if (entry.path().filename().string().front() != '.') inside.push_back(entry.path());
    if (inside.size() == 1 && real_folder(inside.front()) && holds_tasks(inside.front(), kit)) {
      root = inside.front();
      s.notes.push_back("graded the files in " + root.filename().string() + "/, the only folder");
    }
  }
  const std::string linked = "/ is a link to a folder: left out (submit the files themselves)";
  if (fs::is_symlink(root / "tasks")) s.notes.push_back("tasks" + linked);
  fs::path tasks_root = root;
  s.layout = Layout::loose_files;
  if (real_folder(root / "tasks")) {
    s.layout = Layout::repository;
    tasks_root = root / "tasks";
  } else {
    for (const auto& [task, files] : kit.task_files)
      if (real_folder(root / kit.task_folder(task))) s.layout = Layout::tasks_folder;
  }
  for (const auto& [task, files] : kit.task_files) {
    TaskSource& source = s.tasks[task];
    source.folder = s.layout == Layout::loose_files ? root : tasks_root / kit.task_folder(task);
    if (fs::is_symlink(source.folder))
      source.notes.push_back(source.folder.lexically_relative(root).string() + linked);
    if (!real_folder(source.folder)) source.folder.clear();
    for (const std::string& kit_file : files) {
      const std::string name = file_name(kit_file);
      const fs::path path = source.folder / name;
      if (!source.folder.empty() && fs::is_regular_file(fs::symlink_status(path)))
        source.found.push_back(name);
      else
        source.missing.push_back(name);
    }
  }
  return s;
}

TaskCopy copy_task(const Submission& submission, int task, const Kit& kit,
                   const fs::path& destination) {
  const TaskSource& source = submission.tasks.at(task);
  TaskCopy copy;
  copy.notes = source.notes;
  copy.folder = destination / "tasks" / kit.task_folder(task);
  fs::create_directories(copy.folder);
  std::set<std::string> other_tasks_files;
  for (const auto& [n, files] : kit.task_files)
    if (n != task)
      for (const std::string& f : files)
        other_tasks_files.insert(file_name(f));

  // The task's own files always; the submission's other files (its headers) up to a limit, so
  // that no number of extra files can push the task's files out.
  std::vector<fs::path> files, others;
  for (const std::string& name : source.found)
    files.push_back(source.folder / name);
  std::error_code error;
  if (!source.folder.empty())
    for (const fs::directory_entry& entry : fs::directory_iterator(source.folder, error)) {
      const std::string name = entry.path().filename().string();
      const bool kit_file =
          std::find(source.found.begin(), source.found.end(), name) != source.found.end();
      if (kit_file || entry.is_directory() || other_tasks_files.count(name) > 0) continue;
      if (entry.is_symlink()) {
        copy.notes.push_back(name + " is a link, not a file: left out (submit the file itself)");
        continue;
      }
      if (!entry.is_regular_file()) continue;
      if (entry.file_size(error) > largest_file) {
        copy.notes.push_back(name + " is larger than 1 MB: left out");
        continue;
      }
      others.push_back(entry.path());
      const std::string extension = entry.path().extension().string();
      if (extension == ".cpp" || extension == ".cc" || extension == ".cxx")
        copy.notes.push_back(name +
                             " is not compiled: only the kit's files of the task are (put "
                             "helpers in them, or in a header they include)");
    }
  std::sort(others.begin(), others.end());
  if (others.size() > std::size_t(most_files)) {
    copy.notes.push_back(std::to_string(others.size()) + " other files beside the task's: only " +
                         "the first " + std::to_string(most_files) + " are copied");
    others.resize(std::size_t(most_files));
  }
  files.insert(files.end(), others.begin(), others.end());
  for (const std::string& name : source.missing) {
    files.push_back(kit.starter / kit.task_folder(task) / name);
    copy.notes.push_back(name + " is missing: graded as the starter code");
  }
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
  for (const fs::path& file : files) {
    const std::string bytes = read_bytes(file);
    std::ofstream(copy.folder / file.filename(), std::ios::binary) << bytes;
    copy.contents += file.filename().string() + '\0' + std::to_string(bytes.size()) + '\0' + bytes;
  }
  return copy;
}

}  // namespace springlab::grader
