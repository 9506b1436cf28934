#include "results.hpp"

#include "reports.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace springlab::grader {
namespace {

constexpr const char* folder_marker = ".springlab-grade";   // a folder this program may empty
constexpr const char* result_marker = ".springlab-graded";  // a submission's record in it

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::optional<Recorded> read_marker(const fs::path& file) {
  using nlohmann::json;
  const json j = json::parse(read_text(file), nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("name")) return std::nullopt;
  try {
    Recorded r;
    r.name = j.at("name").get<std::string>();
    r.signature = j.at("signature").get<std::string>();
    for (const auto& [task, t] : j.at("tasks").items()) {
      const int n = std::stoi(task);
      r.points[n] = t.at("points").get<double>();
      r.max_points[n] = t.at("max").get<double>();
      if (t.contains("fault")) r.faults[n] = t.at("fault").get<std::string>();
      if (t.contains("review")) r.review[n] = t.at("review").get<std::vector<std::string>>();
    }
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // a marker this version cannot read: graded again
  }
}

std::string marker_text(const Recorded& r) {
  using nlohmann::json;
  json tasks = json::object();
  for (const auto& [task, points] : r.points) {
    json t = {{"points", points}, {"max", r.max_points.at(task)}};
    if (r.faults.count(task) > 0) t["fault"] = r.faults.at(task);
    if (r.review.count(task) > 0) t["review"] = r.review.at(task);
    tasks[std::to_string(task)] = t;
  }
  const json j = {{"name", r.name}, {"signature", r.signature}, {"tasks", tasks}};
  return j.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace

ResultsFolder::ResultsFolder(fs::path out, bool replace) : out_(std::move(out)) {
  std::error_code error;
  if (fs::exists(out_) && !fs::is_directory(out_))
    throw UsageError(escaped(out_.string()) + " exists and is not a folder");
  if (fs::exists(out_) && !fs::is_empty(out_) && !fs::exists(out_ / folder_marker))
    throw UsageError(escaped(out_.string()) + " holds files springlab-grade did not write: " +
                     "choose another folder, or empty it yourself");
  fs::create_directories(out_, error);
  if (error) throw UsageError("cannot make " + escaped(out_.string()) + ": " + error.message());
  // Kept open (and locked) for the rest of the run; close-on-exec, so no test process holds it.
  lock_ = ::open((out_ / folder_marker).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_ < 0)
    throw UsageError("cannot write in " + escaped(out_.string()) + ": " + std::strerror(errno));
  if (::flock(lock_, LOCK_EX | LOCK_NB) != 0)
    throw UsageError(escaped(out_.string()) + " is in use by another springlab-grade run: wait " +
                     "for it to end, or give this run another --out folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(out_)) {
    const std::string name = entry.path().filename().string();
    if (name == folder_marker) continue;
    // What a run that was stopped left half written, and everything with --replace.
    if (replace || name.rfind(".partial-", 0) == 0 || name.find(".partial.") != std::string::npos) {
      fs::remove_all(entry.path(), error);
      if (error)
        throw UsageError("cannot empty " + escaped(out_.string()) + ": " + error.message());
      continue;
    }
    if (entry.is_directory())
      if (auto r = read_marker(entry.path() / result_marker)) recorded_[r->name] = *r;
  }
  const std::string text = "written by springlab-grade; --replace empties it\n";
  if (::ftruncate(lock_, 0) != 0 ||
      ::write(lock_, text.data(), text.size()) != ssize_t(text.size()))
    throw UsageError("cannot write in " + escaped(out_.string()) + ": " + std::strerror(errno));
}

ResultsFolder::~ResultsFolder() {
  if (lock_ >= 0) ::close(lock_);
}

std::optional<Recorded> ResultsFolder::unchanged(const std::string& name,
                                                 const std::string& signature) const {
  const auto it = recorded_.find(name);
  if (it == recorded_.end() || signature.empty() || it->second.signature != signature)
    return std::nullopt;
  // Kept only while its reports are all there.
  const fs::path folder = out_ / results_folder(name);
  for (const char* file : {"feedback.txt", "results.json"})
    if (!fs::exists(folder / file)) return std::nullopt;
  return it->second;
}

void ResultsFolder::write(const SubmissionResult& r, const std::string& signature, const Kit& kit,
                          double seconds) {
  Recorded rec;
  rec.name = r.submission.name;
  rec.signature = signature;
  for (const auto& [task, result] : r.tasks) {
    rec.points[task] = result.points();
    rec.max_points[task] = result.max_points();
    if (!result.fault.empty()) rec.faults[task] = result.fault;
    if (!result.review.empty()) rec.review[task] = result.review;
  }
  // Only a submission graded whole can be kept by a later run: one with a fault never is.
  if (!r.fault().empty()) rec.signature.clear();
  const std::string folder = results_folder(r.submission.name);
  const fs::path partial = out_ / (".partial-" + folder), final = out_ / folder;
  std::error_code error;
  fs::remove_all(partial, error);
  fs::create_directories(partial, error);
  if (error)
    throw std::runtime_error("cannot write " + escaped(partial.string()) + ": " + error.message());
  write_file(partial / "feedback.txt", feedback(r, kit));
  write_file(partial / "results.json", results_json(r, seconds));
  for (const auto& [task, result] : r.tasks)
    write_file(partial / ("task" + std::to_string(task) + ".junit.xml"), junit_report(r, task));
  write_file(partial / result_marker, marker_text(rec));
  fs::remove_all(final, error);
  if (!error) fs::rename(partial, final, error);
  if (error)
    throw std::runtime_error("cannot write " + escaped(final.string()) + ": " + error.message());
  recorded_[rec.name] = rec;
}

void ResultsFolder::write_gradebook(const std::string& note) const {
  std::string book = "submission,task1,task2,task3,task4,task5,total\n", review;
  for (const auto& [name, r] : recorded_) {  // by name
    book += csv(escaped(name));
    double total = 0.0;
    for (int task = 1; task <= 5; ++task) {
      std::string cell;
      if (r.faults.count(task) > 0)
        cell = "not graded";
      else if (r.points.count(task) > 0)
        cell = points_text(r.points.at(task));
      total += r.points.count(task) > 0 ? r.points.at(task) : 0.0;
      book += "," + cell;
    }
    book += "," + (r.faults.empty() ? points_text(total) : std::string("not graded")) + "\n";
    for (const auto& [task, why] : r.faults)
      review += csv(escaped(name)) + "," + std::to_string(task) + "," +
                csv("not graded: " + printable(why)) + "\n";
    for (const auto& [task, calls] : r.review) {
      std::string text;
      for (const std::string& call : calls)
        text += (text.empty() ? "" : "; ") + call;
      review += csv(escaped(name)) + "," + std::to_string(task) + "," + csv(text) + "\n";
    }
  }
  if (!note.empty()) review += "(every submission),," + csv(note) + "\n";
  write_file(out_ / "gradebook.csv", book);
  std::error_code error;
  if (review.empty())
    fs::remove(out_ / "review.csv", error);
  else
    write_file(out_ / "review.csv", "submission,task,calls\n" + review);
}

std::string submission_digest(const Submission& submission, const std::vector<int>& tasks) {
  std::string digest;
  std::error_code error;
  for (const int task : tasks) {
    if (submission.tasks.count(task) == 0) return "";
    const TaskSource& source = submission.tasks.at(task);
    digest += "task " + std::to_string(task) + "\n";
    if (source.folder.empty()) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(source.folder, error))
      if (entry.is_regular_file(error) && !entry.is_symlink(error)) files.push_back(entry.path());
    if (error) return "";
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      if (fs::file_size(file, error) > largest_file || error) {
        digest += file.filename().string() + " (large)\n";
        continue;
      }
      std::ifstream in(file, std::ios::binary);
      if (!in) return "";
      digest += file.filename().string() + " " + file_digest(file) + "\n";
    }
  }
  return digest;
}

}  // namespace springlab::grader
