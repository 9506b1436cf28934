#include "gui/runs.hpp"

#include "springlab/errors.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <utility>
#include <vector>

namespace springlab::view {
namespace {

void save(const sf::Image& image, const std::string& path) {
  if (!image.saveToFile(path))
    throw InvalidParameter("file", path, "a PNG file that can be written");
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

// Mean and p95 of each phase, ms: says where a slow frame's time goes.
void phase_report(const std::vector<FramePhases>& phases, std::ostream& out) {
  const std::pair<const char*, double FramePhases::*> names[] = {
      {"panel", &FramePhases::panel},
      {"stepping", &FramePhases::stepping},
      {"scene", &FramePhases::scene},
      {"imgui", &FramePhases::imgui},
      {"display", &FramePhases::display}};
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

void benchmark_report(const std::vector<double>& frames, long steps, double seconds,
                      double stepping, double simulated, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line,
                "frame time over %zu frames: p50 %.2f ms, p95 %.2f ms, p99 %.2f ms, max %.2f ms\n",
                frames.size(), 1e3 * percentile(frames, 50), 1e3 * percentile(frames, 95),
                1e3 * percentile(frames, 99), 1e3 * percentile(frames, 100));
  out << line;
  std::snprintf(line, sizeof line,
                "%ld steps in %.2f s: %.0f steps/s, %.0f frames/s; stepping %.0f %% of the time\n",
                steps, seconds, double(steps) / seconds, double(frames.size()) / seconds,
                100 * stepping / seconds);
  out << line;
  std::snprintf(line, sizeof line, "simulated %.2f s in %.2f s of wall time (%.2f x real time)\n",
                simulated, seconds, simulated / seconds);
  out << line;
  const bool real_time = percentile(frames, 95) <= 1.0 / 60;
  out << (real_time ? "real time at 60 frames/s: yes (p95 within 16.7 ms)\n"
                    : "real time at 60 frames/s: no (p95 above 16.7 ms)\n");
}

// Said once, when a frame's steps take more than a second: the window then lags far behind the
// simulated time and seems frozen, which a student would otherwise take for a bug.
void warn_if_too_slow(const FrameInfo& frame, bool& warned) {
  if (warned || frame.stepping_seconds <= 1.0) return;
  warned = true;
  char line[256];
  std::snprintf(line, sizeof line,
                "springlab-view: one frame's %ld steps took %.3g s: the viewer cannot keep up "
                "with this scene (a few frames a minute); a smaller grid, a larger step or "
                "another integrator is faster\n",
                frame.steps, frame.stepping_seconds);
  std::fputs(line, stderr);
}

}  // namespace

void print_summary(const Session& session, std::ostream& out) {
  const SceneParameters& p = session.parameters();
  const auto counted = [](std::size_t n, const char* thing) {
    return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
  };
  out << "scene " << p.name << ": " << p.rows << "x" << p.cols << " grid, "
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
  } else {
    out << "no simulation\n";
  }
  if (session.problem().kind != Problem::Kind::none)
    out << session.problem().headline << ": " << session.problem().detail << '\n';
}

int run(App& app, const RunOptions& options, std::ostream& out) {
  if (!options.record.empty()) std::filesystem::create_directories(options.record);
  std::vector<double> frame_seconds;
  std::vector<FramePhases> phases;
  long steps = 0;
  double stepping = 0.0;
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  bool warned_slow = false;
  for (long frame = 0; app.is_open() && (options.frames == 0 || frame < options.frames); ++frame) {
    const bool last_frame = frame + 1 == options.frames;
    app.frame(!options.record.empty() || (last_frame && !options.screenshot.empty()));
    if (!options.record.empty()) save(app.captured(), frame_file(options.record, frame));
    const auto now = std::chrono::steady_clock::now();
    frame_seconds.push_back(std::chrono::duration<double>(now - last).count());
    last = now;
    warn_if_too_slow(app.last_frame(), warned_slow);
    steps += app.last_frame().steps;
    stepping += app.last_frame().stepping_seconds;
    phases.push_back(app.last_frame().phases);
  }
  const double seconds = std::chrono::duration<double>(last - start).count();
  if (!options.screenshot.empty() && app.captured().getSize().x > 0) {
    save(app.captured(), options.screenshot);
  }
  print_summary(app.session(), out);
  if (!options.screenshot.empty()) out << "screenshot: " << options.screenshot << '\n';
  if (!options.record.empty())
    out << "frames: " << frame_file(options.record, 0) << " ... "
        << frame_file(options.record, long(frame_seconds.size()) - 1) << '\n';
  if (options.benchmark && !frame_seconds.empty()) {
    benchmark_report(frame_seconds, steps, seconds, stepping, app.session().time(), out);
    phase_report(phases, out);
  }
  return exit_code(app.session());
}

}  // namespace springlab::view
