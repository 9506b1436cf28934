// springlab-view: the 2D viewer. Interactive by default; with --frames, --screenshot, --record or
// --benchmark it runs a fixed number of frames with no user input (under xvfb-run on a machine
// without a display). Exit codes as springlab-run's (0 done, 1 failed, 2 bad input, 3 diverged,
// 4 a task not written yet, 6 the output could not be written), and 5 when there is no display to
// open a window on.
#include "gui/app.hpp"
#include "gui/display.hpp"
#include "gui/platform.hpp"
#include "gui/runs.hpp"
#include "springlab/cli_values.hpp"
#include "springlab/errors.hpp"
#include "springlab/implementation.hpp"
#include "springlab/integrator.hpp"
#include "springlab/memory_budget.hpp"
#include "springlab/scene.hpp"
#include "springlab/scene_text.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <new>
#include <optional>

namespace {

using namespace springlab;
using namespace springlab::view;

enum Exit { done = 0, failed = 1, bad_input = 2, no_display = 5, lost_output = 6 };

// Input refused in words of its own (not "option = value: allowed ..."): exit 2.
class Refused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

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
  std::optional<std::string> screenshot, record;  // as given: "" is a slip, not "none"
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
    throw InvalidParameter("--size", quoted_for_terminal(text),
                           "WIDTHxHEIGHT in pixels, 640 <= WIDTH <= 8192, 400 <= HEIGHT <= 8192");
  app.width = width;
  app.height = height;
}

// The scene as the options ask for it, checked before a window opens.
SceneParameters scene_from(const Options& options) {
  if (options.compare != "off" && options.impl != "student")
    throw InvalidParameter("--compare", quoted_for_terminal(options.compare),
                           "off with --impl reference: a comparison sets your code beside the "
                           "reference, so add --impl student");
  // An option and a --set of the same parameter: which should win would be a guess.
  refuse_double_settings(options.sets,
                         {{"--dt", "step", options.dt.has_value()},
                          {"--integrator", "integrator", options.integrator.has_value()}});
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
  if (!platform::can_write_in(where))
    throw InvalidParameter(
        option, quoted_for_terminal(path),
        "a path in a folder that exists and can be written (" + where.string() + " is not)");
}

// Proves that the screenshot can be written by opening it as SFML will, before the first frame
// rather than after the last (where SFML's "Failed to save image" did not name the option). A
// file there already is opened without being truncated; one made for the proof is removed again.
void check_writable(const char* option, const std::string& path) {
  if (const std::string why = platform::probe_writable(path); !why.empty())
    throw InvalidParameter(option, quoted_for_terminal(path),
                           "a file that can be written (" + why + ")");
}

// --screenshot and --record, checked before the first frame rather than after the last.
void check_outputs(Options& options) {
  RunOptions& run = options.run;
  // Never over the scene file itself (a scene file named view.png, say).
  std::error_code same;
  for (const auto& [option, path] :
       {std::pair{"--screenshot", options.screenshot}, std::pair{"--record", options.record}})
    if (path && std::filesystem::equivalent(*path, options.app.scene, same))
      throw InvalidParameter(option, quoted_for_terminal(*path),
                             "not the scene file: the images would overwrite the scene");
  if (options.screenshot) refuse_empty_path("--screenshot", *options.screenshot);
  if (options.record) refuse_empty_path("--record", *options.record);
  run.screenshot = options.screenshot.value_or("");
  run.record = options.record.value_or("");
  if (!run.screenshot.empty()) {
    std::string extension = std::filesystem::path(run.screenshot).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".png" && extension != ".bmp" && extension != ".tga" && extension != ".jpg" &&
        extension != ".jpeg")
      throw InvalidParameter("--screenshot", quoted_for_terminal(run.screenshot),
                             "a file ending in .png, .bmp, .tga, .jpg or .jpeg");
    check_folder("--screenshot", run.screenshot,
                 std::filesystem::path(run.screenshot).parent_path());
    check_writable("--screenshot", run.screenshot);
  }
  if (!run.record.empty()) {
    std::error_code error;
    std::filesystem::create_directories(run.record, error);
    check_folder("--record", run.record, run.record);
  }
}

constexpr double mib = 1024.0 * 1024.0;

// The memory the window takes on top of what the process holds when it checks, before the window
// opens: Mesa's software renderer (llvmpipe loads LLVM and starts its threads, 8 MiB of stack
// each), SFML's X connection and ImGui's font atlas. Measured with task1 and task5 headless under
// Xvfb (Debian 12, Mesa 22.3, one malloc arena as main sets under a limit): the smallest
// `ulimit -v` that runs them is 281 MiB, 15.5 of it mapped at the check; the smallest `ulimit -d`
// 76 MiB, under 1 in use at the check; the resident size of the whole process stays under
// 96 MiB. The margin covers other machines' libraries and drivers.
constexpr double window_address_space = 270 * mib, window_memory = 96 * mib, margin = 64 * mib;

// A window that does not fit in the memory the process may have is refused before it opens:
// Mesa and ImGui do not check every allocation, and a failed one was a segmentation fault or a
// corrupted heap, not a message. The scene's own estimate comes on top of the window's.
void check_window_memory(const SceneParameters& p) {
  const double scene = estimated_bytes(p);
  if (const std::optional<double> address_space = platform::address_space_limit()) {
    const double needed =
        address_space_in_use() + window_address_space + margin + scene + thread_stack_bytes(p);
    if (needed > *address_space)
      throw Refused("the window needs " + mebibytes_text(needed) +
                    " of address space; the limit is " +
                    std::to_string(std::llround(*address_space / mib)) + " MiB" +
                    " (ulimit -v): raise the limit, or run springlab-run, which needs no window");
  }
  const MemoryLimit limit = available_memory();
  const double needed = window_memory + margin + scene;
  if (needed > limit.bytes)
    throw Refused("the window needs " + mebibytes_text(needed) + " of memory; " +
                  mebibytes_text(limit.bytes) + " are free (" + limit.source +
                  "): allow the process more memory, or run springlab-run, which needs no window");
}

// Mesa's software OpenGL (llvmpipe) rasterises in a thread per core by default: beside the
// stepping thread, those took its core in every frame's display, and a 200x200 fabric's Verlet
// step took 15 ms instead of 10.7 (Xvfb, 2 cores, idle). With LP_NUM_THREADS=0 the window's
// thread rasterises itself, so stepping and drawing keep a core each. Set before the window's
// context exists; a value the user set wins; other drivers ignore it.
void rasterise_in_the_drawing_thread() {
  platform::set_environment_default("LP_NUM_THREADS", "0");
}

int open_viewer(Options& options) {
  parse_size(options.size, options.app);
  read_numbers(options);
  check_outputs(options);
  const SceneParameters p = scene_from(options);
  const bool headless = options.run.frames > 0 || !options.run.screenshot.empty() ||
                        !options.run.record.empty() || options.run.benchmark;
  if (headless && options.run.frames == 0) options.run.frames = options.run.benchmark ? 600 : 120;
  if (!display_reachable(std::cerr)) {
    std::cerr << "springlab-view: no display, so no window can open.\n"
                 "Run it headless under Xvfb instead, e.g.\n"
                 "  xvfb-run -a springlab-view --scene "
              << printable(options.app.scene) << " --frames 120 --screenshot view.png\n";
    return no_display;
  }
  check_window_memory(p);
  options.run.terminal = platform::standard_error_is_terminal();
  options.app.frame_rate_limit = !headless;
  options.app.fixed_frame_time = headless && !options.run.benchmark;
  if (!options.app.fixed_frame_time) rasterise_in_the_drawing_thread();
  App app(options.app);
  Session& session = app.session();
  session.parameters() = p;
  Pacing& pacing = session.pacing();
  if (options.real_time_factor_value) pacing.real_time_factor = *options.real_time_factor_value;
  if (options.steps_per_frame_value)
    pacing.real_time = false, pacing.steps_per_frame = *options.steps_per_frame_value;
  // A headless run takes exactly 1/60 s of the scene a frame, as the README promises, however
  // many steps that is: the cap that keeps a window responsive has no window to serve.
  if (options.app.fixed_frame_time) pacing.max_steps_per_frame = std::numeric_limits<long>::max();
  session.set_code(options.impl == "student" ? Code::student : Code::reference);
  if (options.compare != "off" && !reference_is_available())
    std::cerr << "springlab-view: --compare " << printable(options.compare)
              << " is off: this build has no reference to compare with (its prebuilt reference "
                 "was made for another compiler or processor; the build's first message says "
                 "which)\n";
  session.set_compare(options.compare == "overlay"        ? Compare::overlay
                      : options.compare == "side-by-side" ? Compare::side_by_side
                                                          : Compare::off);
  session.reset();
  if (options.paused) session.set_running(false);
  return run(app, options.run, std::cout, std::cerr);
}

// Standard output lost (a full disk, a closed pipe): an error, not a silent exit 0. For --help;
// run() checks the summary's output itself.
int checked_stdout(int code) {
  const std::string failure = flush_failure(std::cout);
  if (failure.empty()) return code;
  std::cerr << "springlab-view: " << failure << '\n';
  return code == done ? lost_output : code;
}

// CLI11 2.5 and later reflow the footer into one paragraph by default, which breaks its lines
// mid-sentence; earlier versions print it as written, and have no such setting.
template <class Formatter>
void footer_as_written(Formatter& formatter) {
  if constexpr (requires { formatter.enable_footer_formatting(false); })
    formatter.enable_footer_formatting(false);
}

constexpr const char* exit_codes =
    "\nExit codes: 0 done, 2 bad input, 3 the run diverged, 4 a task not written yet, 5 no "
    "display, 6 the output could not be written (a full disk, a closed pipe); 1 an unexpected "
    "error.\nHeadless runs that last more than a few seconds show their progress on stderr; one "
    "that would last more than a few minutes says so first.";

// The command line: the options in the order --help lists them, and its footer (the
// integrators, the window's keys, the exit codes).
void add_options(CLI::App& cli, Options& options) {
  cli.add_option("--scene", options.app.scene,
                 "task1 ... task5, task4-damped or a scene file (TOML)")
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
  cli.add_option("--screenshot", options.screenshot, "save the last frame as this PNG file");
  cli.add_option("--record", options.record, "save every frame into this directory");
  cli.add_flag("--benchmark", options.run.benchmark,
               "no frame-rate limit; report frame-time percentiles and steps per second");
  cli.add_option("--size", options.size, "window size in pixels")->capture_default_str();
  cli.add_flag("--paused", options.paused, "start paused");
  std::string integrators;
  for (const std::string& name : integrator_names())
    integrators += " " + name;
  footer_as_written(*cli.get_formatter());
  cli.footer("Integrators:" + integrators +
             "\nIn the window: drag a particle to move it, right-click to pin or unpin it, "
             "shift+click to push it;\nwheel to zoom, drag the background to pan; space runs or "
             "pauses, S steps once, R resets, F fits the view." +
             exit_codes);
}

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe is then a write error, reported with exit 6, not a silent death by SIGPIPE.
  platform::ignore_broken_pipes();
  // Under an address-space limit (ulimit -v), glibc's malloc reserves 64 MiB of it for each thread
  // that allocates (llvmpipe's included): whether the window then fitted, and which allocation
  // failed, changed from run to run and from limit to limit (600 MB crashed, 650 MB ran). One
  // arena makes the window's need a fixed amount, which check_window_memory compares with the
  // limit.
  platform::one_arena_under_memory_limits();
  Options options;
  CLI::App cli{"springlab-view: watch, steer and diagnose a springlab scene in a window"};
  add_options(cli, options);
  // Every message through printable_lines: the user's text in it (a scene name, a path) cannot
  // command the terminal (ESC).
  const auto say = [](const std::string& message) {
    std::cerr << "springlab-view: " << printable_lines(message) << '\n';
  };
  try {
    cli.parse(argc, argv);
  } catch (const CLI::Success& help) {
    return checked_stdout(cli.exit(help));
  } catch (const CLI::ParseError& error) {
    say(std::string(error.what()) + " (springlab-view --help lists the options)");
    return bad_input;
  }
  try {
    return open_viewer(options);  // run() checks standard output itself
  } catch (const OutputLost& error) {
    say(error.what());
    return lost_output;
  } catch (const InvalidParameter& error) {
    say(error.what());
    return bad_input;
  } catch (const Refused& error) {
    say(error.what());
    return bad_input;
  } catch (const std::bad_alloc&) {
    const MemoryLimit limit = available_memory();
    say("ran out of memory; " + mebibytes_text(limit.bytes) + " are free now (" + limit.source +
        "): make the grid or the window smaller, or allow the process more memory");
    return bad_input;
  } catch (const std::exception& error) {
    say(std::string("stopped on an unexpected error: ") + error.what());
    return failed;
  }
}
