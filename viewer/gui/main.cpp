// springlab-view: the 2D viewer. Interactive by default; with --frames, --screenshot, --record or
// --benchmark it runs a fixed number of frames with no user input (under xvfb-run on a machine
// without a display). Exit codes as springlab-run's (0 done, 1 failed, 2 bad input, 3 diverged,
// 4 a task not written yet), and 5 when there is no display to open a window on.
#include "gui/app.hpp"
#include "gui/display.hpp"
#include "gui/runs.hpp"
#include "springlab/cli_values.hpp"
#include "springlab/errors.hpp"
#include "springlab/implementation.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>

namespace {

using namespace springlab;
using namespace springlab::view;

constexpr int bad_input = 2, no_display = 5;

struct Options {
  AppOptions app;
  RunOptions run;
  std::string impl = "reference";
  std::string compare = "off";
  std::optional<std::string> integrator;
  // Numbers as written, read by option_number: CLI11 would take "nan", and "" for the default.
  std::optional<std::string> dt, real_time_factor, steps_per_frame, frames;
  std::optional<double> real_time_factor_value;
  std::optional<int> steps_per_frame_value;
  std::vector<std::string> sets;
  std::string size = "1280x800";
  bool paused = false;
};

void parse_size(const std::string& text, AppOptions& app) {
  const auto x = text.find('x');
  unsigned width = 0, height = 0;
  const char* end = text.data() + text.size();
  const bool ok = x != std::string::npos &&
                  std::from_chars(text.data(), text.data() + x, width).ptr == text.data() + x &&
                  std::from_chars(text.data() + x + 1, end, height).ptr == end;
  if (!ok || width < 640 || width > 8192 || height < 400 || height > 8192)
    throw InvalidParameter("--size", "\"" + text + "\"",
                           "WIDTHxHEIGHT in pixels, 640 <= WIDTH <= 8192, 400 <= HEIGHT <= 8192");
  app.width = width;
  app.height = height;
}

// The scene as the options ask for it, checked before a window opens.
SceneParameters scene_from(const Options& options) {
  SceneParameters p = load_scene(options.app.scene);
  if (options.integrator) set_parameter(p, "integrator", *options.integrator);
  if (options.dt)
    set_number(p, "step", option_number("--dt", *options.dt, parameter_range("step"), "s"));
  for (const std::string& assignment : options.sets)
    set_assignment(p, assignment);
  validate(p);
  return p;
}

// Every number, read before a window opens.
void read_numbers(Options& options) {
  if (options.real_time_factor)
    options.real_time_factor_value =
        option_number("--real-time-factor", *options.real_time_factor, Range{0.001, 1000.0});
  if (options.steps_per_frame)
    options.steps_per_frame_value = int(option_number("--steps-per-frame", *options.steps_per_frame,
                                                      Range{1, 100000, false, false, true}));
  if (options.frames)
    options.run.frames =
        long(option_number("--frames", *options.frames, Range{1, 1e8, false, false, true}));
}

// The folder of a file to be written: it exists and may be written in.
void check_folder(const char* option, const std::string& path,
                  const std::filesystem::path& folder) {
  const std::filesystem::path where = folder.empty() ? "." : folder;
  std::error_code error;
  if (!std::filesystem::is_directory(where, error) || access(where.c_str(), W_OK) != 0)
    throw InvalidParameter(
        option, "\"" + path + "\"",
        "a path in a folder that exists and can be written (" + where.string() + " is not)");
}

// --screenshot and --record, checked before the first frame rather than after the last.
void check_outputs(const RunOptions& run) {
  if (!run.screenshot.empty()) {
    std::string extension = std::filesystem::path(run.screenshot).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".png" && extension != ".bmp" && extension != ".tga" && extension != ".jpg" &&
        extension != ".jpeg")
      throw InvalidParameter("--screenshot", "\"" + run.screenshot + "\"",
                             "a file ending in .png, .bmp, .tga, .jpg or .jpeg");
    check_folder("--screenshot", run.screenshot,
                 std::filesystem::path(run.screenshot).parent_path());
  }
  if (!run.record.empty()) {
    std::error_code error;
    std::filesystem::create_directories(run.record, error);
    check_folder("--record", run.record, run.record);
  }
}

int open_viewer(Options& options) {
  parse_size(options.size, options.app);
  read_numbers(options);
  check_outputs(options.run);
  const SceneParameters p = scene_from(options);
  const bool headless = options.run.frames > 0 || !options.run.screenshot.empty() ||
                        !options.run.record.empty() || options.run.benchmark;
  if (headless && options.run.frames == 0) options.run.frames = options.run.benchmark ? 600 : 120;
  if (!display_reachable(std::cerr)) {
    std::cerr << "springlab-view: no display, so no window can open.\n"
                 "Run it headless under Xvfb instead, e.g.\n"
                 "  xvfb-run -a springlab-view --scene "
              << options.app.scene << " --frames 120 --screenshot view.png\n";
    return no_display;
  }
  options.app.frame_rate_limit = !headless;
  options.app.fixed_frame_time = headless && !options.run.benchmark;
  App app(options.app);
  Session& session = app.session();
  session.parameters() = p;
  Pacing& pacing = session.pacing();
  if (options.real_time_factor_value) pacing.real_time_factor = *options.real_time_factor_value;
  if (options.steps_per_frame_value)
    pacing.real_time = false, pacing.steps_per_frame = *options.steps_per_frame_value;
  session.set_code(options.impl == "student" ? Code::student : Code::reference);
  if (options.compare != "off" && !reference_is_available())
    std::cerr << "springlab-view: --compare " << options.compare
              << " is off: this build has no reference to compare with (its prebuilt reference "
                 "was made for another compiler or processor; the build's first message says "
                 "which)\n";
  session.set_compare(options.compare == "overlay"        ? Compare::overlay
                      : options.compare == "side-by-side" ? Compare::side_by_side
                                                          : Compare::off);
  session.reset();
  if (options.paused) session.set_running(false);
  return run(app, options.run, std::cout);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App cli{"springlab-view: watch, steer and diagnose a springlab scene in a window"};
  cli.add_option("--scene", options.app.scene, "task1 ... task5 or a scene file (TOML)")
      ->capture_default_str();
  cli.add_option("--impl", options.impl, "whose code runs: the reference or the student's")
      ->check(CLI::IsMember({"reference", "student"}))
      ->capture_default_str();
  cli.add_option("--compare", options.compare,
                 "with --impl student, run the reference beside it: off, overlay, side-by-side")
      ->check(CLI::IsMember({"off", "overlay", "side-by-side"}))
      ->capture_default_str();
  cli.add_option("--integrator", options.integrator, "an integrator (default: the scene's)");
  cli.add_option("--dt", options.dt, "the step h in seconds, the scene's `step`");
  cli.add_option("--set", options.sets, "KEY=VALUE: change a scene parameter, e.g. structural.k=40")
      ->take_all();
  cli.add_option("--real-time-factor", options.real_time_factor,
                 "simulated seconds per second of wall time, 0.001 to 1000 (default 1)");
  cli.add_option("--steps-per-frame", options.steps_per_frame,
                 "a fixed number of steps a frame instead of real time, 1 to 100000");
  cli.add_option("--frames", options.frames,
                 "run this many frames with no user input, then exit (default with --screenshot "
                 "or --record: 120; with --benchmark: 600)");
  cli.add_option("--screenshot", options.run.screenshot, "save the last frame as this PNG file");
  cli.add_option("--record", options.run.record, "save every frame into this directory");
  cli.add_flag("--benchmark", options.run.benchmark,
               "no frame-rate limit; report frame-time percentiles and steps per second");
  cli.add_option("--size", options.size, "window size in pixels")->capture_default_str();
  cli.add_flag("--paused", options.paused, "start paused");
  std::string integrators;
  for (const std::string& name : integrator_names())
    integrators += " " + name;
  cli.footer("Integrators:" + integrators +
             "\nIn the window: drag a particle to move it, right-click to pin or unpin it, "
             "shift+click to push it;\nwheel to zoom, drag the background to pan; space runs or "
             "pauses, S steps once, R resets, F fits the view.");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::Success& help) {
    return cli.exit(help);
  } catch (const CLI::ParseError& error) {
    std::cerr << "springlab-view: " << error.what()
              << " (springlab-view --help lists the options)\n";
    return bad_input;
  }
  try {
    return open_viewer(options);
  } catch (const InvalidParameter& error) {
    std::cerr << "springlab-view: " << error.what() << '\n';
    return bad_input;
  } catch (const std::exception& error) {
    std::cerr << "springlab-view: stopped on an unexpected error: " << error.what() << '\n';
    return 1;
  }
}
