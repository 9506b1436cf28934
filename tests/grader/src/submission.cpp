#include "submission.hpp"

#include "reports.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace springlab::grader {
namespace {

constexpr int most_files = 64;  // files copied per task folder

std::string file_name(const std::string& kit_path) {
  return kit_path.substr(kit_path.find('/') + 1);
}

std::string size_text(std::uintmax_t bytes) {
  std::ostringstream text;
  text.precision(3);
  text << double(bytes) / double(1 << 20) << " MB";
  return text.str();
}

}  // namespace

std::string file_digest(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a
  std::uintmax_t size = 0;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i)
      hash = (hash ^ static_cast<unsigned char>(buffer[i])) * 1099511628211ull;
    size += std::uintmax_t(in.gcount());
  }
  return std::to_string(size) + ":" + std::to_string(hash);
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::ifstream in_a(a, std::ios::binary), in_b(b, std::ios::binary);
  if (!in_a || !in_b) return false;
  std::vector<char> buffer_a(65536), buffer_b(65536);
  while (true) {
    in_a.read(buffer_a.data(), std::streamsize(buffer_a.size()));
    in_b.read(buffer_b.data(), std::streamsize(buffer_b.size()));
    if (in_a.gcount() != in_b.gcount() ||
        !std::equal(buffer_a.begin(), buffer_a.begin() + in_a.gcount(), buffer_b.begin()))
      return false;
    if (in_a.gcount() == 0) return true;
  }
}

bool same_files(const fs::path& a, const fs::path& b) {
  std::error_code error;
  std::set<std::string> names_a, names_b;
  for (const auto& e : fs::directory_iterator(a, error))
    names_a.insert(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(b, error))
    names_b.insert(e.path().filename().string());
  return names_a == names_b && std::all_of(names_a.begin(), names_a.end(), [&](const auto& name) {
           return same_file(a / name, b / name);
         });
}

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
    throw UsageError("submission '" + escaped(folder.string()) + "': not a folder");
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
      s.notes.push_back("graded the files in " + escaped(root.filename().string()) +
                        "/, the only folder");
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
      source.notes.push_back(escaped(source.folder.lexically_relative(root).string()) + linked);
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
  std::error_code error;
  for (const std::string& name : source.found) {
    // Throws when the file is gone or cannot be read: the grader's fault, not the student's.
    const std::uintmax_t size = fs::file_size(source.folder / name);
    if (size > largest_file) {
      copy.problem = escaped(name) + " is " + size_text(size) +
                     ": a task's file may have at most " + size_text(largest_file);
      return copy;
    }
    files.push_back(source.folder / name);
  }
  if (!source.folder.empty())
    for (const fs::directory_entry& entry : fs::directory_iterator(source.folder, error)) {
      const std::string name = entry.path().filename().string();
      const bool kit_file =
          std::find(source.found.begin(), source.found.end(), name) != source.found.end();
      if (kit_file || entry.is_directory() || other_tasks_files.count(name) > 0) continue;
      if (entry.is_symlink()) {
        copy.notes.push_back(escaped(name) +
                             " is a link, not a file: left out (submit the file itself)");
        continue;
      }
      if (!entry.is_regular_file()) continue;
      if (entry.file_size(error) > largest_file) {
        copy.notes.push_back(escaped(name) + " is larger than 1 MB: left out");
        continue;
      }
      others.push_back(entry.path());
      const std::string extension = entry.path().extension().string();
      if (extension == ".cpp" || extension == ".cc" || extension == ".cxx")
        copy.notes.push_back(escaped(name) +
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
  // Readable by the user submission code runs as (the sandbox's), whatever the umask.
  fs::permissions(copy.folder, fs::perms::owner_all | fs::perms::group_read |
                                   fs::perms::group_exec | fs::perms::others_read |
                                   fs::perms::others_exec);
  for (const fs::path& file : files) {
    const fs::path target = copy.folder / file.filename();
    fs::copy_file(file, target, fs::copy_options::overwrite_existing);
    fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                                fs::perms::others_read);
    copy.digest += file.filename().string() + '\0' + file_digest(target) + '\0';
  }
  return copy;
}

}  // namespace springlab::grader
