#include "gui/runs.hpp"

#include "springlab/cli_values.hpp"
#include "springlab/progress.hpp"
#include "springlab/scene_text.hpp"

#include <SFML/System/Err.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <ostream>
#include <utility>
#include <vector>

namespace springlab::view {
namespace {

// SFML 2.5's Image::saveToFile does not check its writes (stb_image_write ignores what fwrite and
// fclose say): a full disk left a truncated image behind a run that said it was done. The file is
// read back and its size compared with the image's; an incomplete file is removed rather than
// left looking like output. `lost` says which option's file it was, for the message.
void save(const sf::Image& image, const std::string& path, const std::string& lost) {
  bool written = false;
  {
    // SFML's own "Failed to save/load image" would only repeat ours, without the option.
    std::streambuf* const messages = sf::err().rdbuf(nullptr);
    sf::Image back;
    written =
        image.saveToFile(path) && back.loadFromFile(path) && back.getSize() == image.getSize();
    sf::err().rdbuf(messages);
  }
  if (written) return;
  std::error_code error;
  if (!std::filesystem::is_symlink(path, error) && std::filesystem::is_regular_file(path, error))
    std::filesystem::remove(path, error);
  throw OutputLost(lost + " could not be written in full (is the disk full?)");
}

std::string frame_file(const std::string& directory, long frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05ld.png", frame);
  return (std::filesystem::path(directory) / name).string();
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const auto at = std::size_t(std::lround(p / 100 * double(values.size() - 1)));
  return values[at];
}

int exit_code(const Session& session) {
  switch (session.problem().kind) {
    case Problem::Kind::diverged:
      return 3;
    case Problem::Kind::not_implemented:
      return 4;
    case Problem::Kind::invalid:
      return 2;
    case Problem::Kind::failed:
      return 1;
    case Problem::Kind::none:
      break;
  }
  return 0;
}

// Mean and p95 of each phase, ms: says where a slow frame's time goes. With a stepping thread,
// "stepping" is the window's wait for it and "stepping thread" the thread's own time, on the
// other core.
void phase_report(const std::vector<FramePhases>& phases, bool thread, std::ostream& out) {
  std::vector<std::pair<const char*, double FramePhases::*>> names = {
      {"panel", &FramePhases::panel},
      {"stepping", &FramePhases::stepping},
      {"scene", &FramePhases::scene},
      {"imgui", &FramePhases::imgui},
      {"display", &FramePhases::display}};
  if (thread) names.emplace_back("stepping thread", &FramePhases::thread);
  out << "phases, mean / p95 ms:";
  for (const auto& [name, member] : names) {
    std::vector<double> values;
    values.reserve(phases.size());
    for (const FramePhases& p : phases)
      values.push_back(p.*member);
    double sum = 0.0;
    for (double v : values)
      sum += v;
    char text[64];
    std::snprintf(text, sizeof text, " %s %.2f / %.2f", name, 1e3 * sum / double(values.size()),
                  1e3 * percentile(values, 95));
    out << text;
  }
  out << '\n';
}

void benchmark_report(const std::vector<double>& frames, long steps, long dropped, double seconds,
                      double stepping, double simulated, bool thread, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line,
                "frame time over %zu frames: p50 %.2f ms, p95 %.2f ms, p99 %.2f ms, max %.2f ms\n",
                frames.size(), 1e3 * percentile(frames, 50), 1e3 * percentile(frames, 95),
                1e3 * percentile(frames, 99), 1e3 * percentile(frames, 100));
  out << line;
  std::snprintf(
      line, sizeof line,
      "%ld steps in %.2f s: %.0f steps/s, %.0f frames/s; stepping %.0f %% of the time%s\n", steps,
      seconds, double(steps) / seconds, double(frames.size()) / seconds, 100 * stepping / seconds,
      thread ? " (in its own thread)" : "");
  out << line;
  std::snprintf(line, sizeof line,
                "simulated %.2f s in %.2f s of wall time (%.2f x real time); %ld steps dropped\n",
                simulated, seconds, simulated / seconds, dropped);
  out << line;
  const bool real_time = percentile(frames, 95) <= 1.0 / 60;
  out << (real_time ? "real time at 60 frames/s: yes (p95 within 16.7 ms)\n"
                    : "real time at 60 frames/s: no (p95 above 16.7 ms)\n");
}

// What a headless run of a fixed number of frames says on stderr while it goes on (progress.hpp):
// a run of a million frames is not minutes of silence.
Progress::Settings frame_progress(bool terminal) {
  Progress::Settings settings;
  settings.program = "springlab-view";
  settings.unit = "frame";
  settings.shorten = "ask for fewer --frames";
  settings.terminal = terminal;
  return settings;
}

// Said once, when a frame's steps take more than a second: the window then lags far behind the
// simulated time and seems frozen, which a student would otherwise take for a bug.
void warn_if_too_slow(const FrameInfo& frame, bool& warned, std::optional<Progress>& progress,
                      std::ostream& err) {
  if (warned || frame.stepping_seconds <= 1.0) return;
  warned = true;
  char line[256];
  std::snprintf(line, sizeof line,
                "springlab-view: one frame's %ld steps took %.3g s: the viewer cannot keep up "
                "with this scene (a few frames a minute); a smaller grid, a larger step or "
                "another integrator is faster\n",
                frame.steps, frame.stepping_seconds);
  if (progress) progress->finish();
  err << line << std::flush;
}

}  // namespace

void print_summary(const Session& session, std::ostream& out) {
  const SceneParameters& p = session.parameters();
  const auto counted = [](std::size_t n, const char* thing) {
    return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
  };
  out << "scene " << printable(p.name) << ": " << p.rows << "x" << p.cols << " grid, "
      << counted(std::size_t(p.rows * p.cols), "particle") << ", ";
  if (const Simulation* sim = session.primary()) {
    const Diagnostics d = sim->diagnostics();
    const int task = sim->implementation().student_task;
    out << counted(sim->scene().springs.size(), "spring") << "\n"
        << "code: "
        << (task == 0 ? std::string("the reference")
                      : "your task " + std::to_string(task) + " code, the reference for the rest")
        << "; integrator " << p.integrator << ", h = " << p.step << " s, t = " << session.time()
        << " s; energy " << d.total() << " J ("
        << energy_parts(d, sim->parameters().gravity.enabled) << ")\n";
    // Beside the reference (--compare): the same words as the runner's summary.
    if (const std::optional<Comparison> c = session.comparison()) {
      out << "reference: the same run with the reference's code: yours " << comparison_figures(*c)
          << "\n";
      if (!c->remark.empty()) out << "remark: " << c->remark << "\n";
    }
  } else {
    out << "no simulation\n";
  }
}

void print_problem(const Session& session, std::ostream& err) {
  const Problem& problem = session.problem();
  if (problem.kind == Problem::Kind::none) return;
  // The error's own words already say "Task N is not implemented yet": not twice.
  const std::string text = problem.kind == Problem::Kind::not_implemented
                               ? problem.detail
                               : problem.headline + ": " + problem.detail;
  err << "springlab-view: " << printable_lines(text) << '\n';
}

int run(App& app, const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.record.empty()) std::filesystem::create_directories(options.record);
  const std::string record = "--record = " + quoted_for_terminal(options.record) + ": ";
  std::vector<double> frame_seconds;
  std::vector<FramePhases> phases;
  long steps = 0;
  double stepping = 0.0;
  long dropped = 0;  // steps owed that no frame took (slower than real time)
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  bool warned_slow = false;
  std::optional<Progress> progress;
  if (options.frames > 0) progress.emplace(options.frames, err, frame_progress(options.terminal));
  for (long frame = 0; app.is_open() && (options.frames == 0 || frame < options.frames); ++frame) {
    const bool last_frame = frame + 1 == options.frames;
    app.frame(!options.record.empty() || (last_frame && !options.screenshot.empty()));
    if (!options.record.empty()) {
      const std::string file = frame_file(options.record, frame);
      save(app.captured(), file, record + printable(file));
    }
    const auto now = std::chrono::steady_clock::now();
    frame_seconds.push_back(std::chrono::duration<double>(now - last).count());
    last = now;
    warn_if_too_slow(app.last_frame(), warned_slow, progress, err);
    steps += app.last_frame().steps;
    dropped += app.last_frame().dropped_steps;
    stepping += app.last_frame().stepping_seconds;
    phases.push_back(app.last_frame().phases);
    if (progress) progress->after(frame + 1);
  }
  if (progress) progress->finish();
  // The last frame's steps, still under way in a stepping thread, count in the wall time too.
  app.finish_stepping();
  if (app.stepping_thread() && !frame_seconds.empty()) {
    last = std::chrono::steady_clock::now();
    stepping += app.take_stepping_seconds();  // a frame reads its steps' time one frame late
  }
  const double seconds = std::chrono::duration<double>(last - start).count();
  if (!options.screenshot.empty() && app.captured().getSize().x > 0)
    save(app.captured(), options.screenshot,
         "--screenshot = " + quoted_for_terminal(options.screenshot) + ": the image");
  print_summary(app.session(), out);
  if (!options.screenshot.empty()) out << "screenshot: " << printable(options.screenshot) << '\n';
  if (!options.record.empty())
    out << "frames: " << printable(frame_file(options.record, 0)) << " ... "
        << printable(frame_file(options.record, long(frame_seconds.size()) - 1)) << '\n';
  // Frames with nothing to keep: said, so that a missing image is not a surprise.
  if (options.screenshot.empty() && options.record.empty() && !options.benchmark)
    out << "frames: " << frame_seconds.size()
        << " run without a window's input; nothing saved (--screenshot FILE keeps the last "
           "frame, --record FOLDER every frame)\n";
  if (options.benchmark && !frame_seconds.empty()) {
    benchmark_report(frame_seconds, steps, dropped, seconds, stepping, app.session().time(),
                     app.stepping_thread(), out);
    phase_report(phases, app.stepping_thread(), out);
  }
  // Checked here, while errno still says why: a full disk or a closed pipe loses the summary, and
  // a run that says nothing of it is not done (exit 6). The problem, if any, keeps its own code.
  const std::string failure = flush_failure(out);
  print_problem(app.session(), err);
  const int code = exit_code(app.session());
  if (failure.empty()) return code;
  err << "springlab-view: " << failure << '\n';
  return code == 0 ? 6 : code;
}

}  // namespace springlab::view
