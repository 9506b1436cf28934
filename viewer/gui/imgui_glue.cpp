#include "gui/imgui_glue.hpp"

#include <imgui.h>
#include <imgui_impl_opengl2.h>

#include <array>
#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

namespace springlab::view {
namespace {

using Kind = compat::Input::Kind;

// ImGui's own font lacks the symbols the kit writes (ℓ0, ω, ≈, —); DejaVu Sans has them all.
constexpr float font_pixels = 15.0f;
const ImWchar glyph_ranges[] = {
    0x0020, 0x00FF,  // Latin-1: ×, ², ·, …
    0x0394, 0x03C9,  // Greek: Δ, λ, ω
    0x2013, 0x2026,  // dashes, bullets, ellipsis
    0x2080, 0x2089,  // subscript digits: ℓ₀
    0x2113, 0x2113,  // ℓ
    0x2190, 0x2193,  // arrows
    0x2248, 0x2265,  // ≈, ≤, ≥
    0,
};

// The panel's font, tried in order: DejaVu Sans where each system's packages put it, then a font
// the system comes with. The kit ships none.
std::vector<std::filesystem::path> font_candidates() {
#if defined(_WIN32)
  const char* windows = std::getenv("WINDIR");
  const std::filesystem::path fonts =
      std::filesystem::path(windows && *windows ? windows : "C:/Windows") / "Fonts";
  return {fonts / "DejaVuSans.ttf", fonts / "segoeui.ttf", fonts / "arial.ttf"};
#elif defined(__APPLE__)
  std::vector<std::filesystem::path> files;
  if (const char* home = std::getenv("HOME"); home && *home)  // Homebrew's font-dejavu
    files.push_back(std::filesystem::path(home) / "Library/Fonts/DejaVuSans.ttf");
  for (const char* file :
       {"/Library/Fonts/DejaVuSans.ttf", "/System/Library/Fonts/Supplemental/Arial Unicode.ttf",
        "/Library/Fonts/Arial Unicode.ttf", "/System/Library/Fonts/Supplemental/Arial.ttf"})
    files.emplace_back(file);
  return files;
#else
  return {
      "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",    // Debian, Ubuntu
      "/usr/share/fonts/TTF/DejaVuSans.ttf",                // Arch
      "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",  // Fedora
      "/usr/share/fonts/dejavu/DejaVuSans.ttf",             // Alpine
      "/usr/share/fonts/truetype/DejaVuSans.ttf",           // openSUSE
      "/usr/local/share/fonts/dejavu/DejaVuSans.ttf",       // FreeBSD
      "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
      "/usr/share/fonts/liberation-sans/LiberationSans-Regular.ttf",
      "/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf",
      "/usr/share/fonts/noto/NotoSans-Regular.ttf",
  };
#endif
}

// The first font file that can be read, or "" after saying (once a program) that there is none.
// Checked here: ImGui asserts on a file it cannot open.
std::string panel_font() {
  const std::vector<std::filesystem::path> candidates = font_candidates();
  for (const std::filesystem::path& file : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(file, error) && std::ifstream(file, std::ios::binary))
      return file.string();
  }
  static bool said = false;
  if (!said) {
    said = true;
    std::cerr << "springlab-view: found no font for the panel (looked for "
              << candidates.front().string() << " and " << candidates.size() - 1
              << " others): it uses Dear ImGui's own, which lacks the symbols ω, ≈, ℓ and —. "
                 "Installing DejaVu Sans brings them back.\n";
  }
  return "";
}

int button_index(sf::Mouse::Button button) {
  switch (button) {
    case sf::Mouse::Button::Left:
      return 0;
    case sf::Mouse::Button::Right:
      return 1;
    case sf::Mouse::Button::Middle:
      return 2;
    default:
      return -1;
  }
}

#if IMGUI_VERSION_NUM >= 18700
// ImGui 1.87 and later: input as events, queued until the next frame. A press and its release
// within one frame reach the widgets in two frames (ImGui's input trickling), so a click counts.
#if IMGUI_VERSION_NUM >= 18823
constexpr ImGuiKey mod_ctrl = ImGuiMod_Ctrl, mod_shift = ImGuiMod_Shift, mod_alt = ImGuiMod_Alt,
                   mod_super = ImGuiMod_Super;
#else  // the same keys' names in 1.87 and 1.88
constexpr ImGuiKey mod_ctrl = ImGuiKey_ModCtrl, mod_shift = ImGuiKey_ModShift,
                   mod_alt = ImGuiKey_ModAlt, mod_super = ImGuiKey_ModSuper;
#endif

// The keys ImGui's widgets use: text editing, navigation and the clipboard's shortcuts.
ImGuiKey imgui_key(sf::Keyboard::Key key) {
  using K = sf::Keyboard::Key;
  switch (key) {
    case K::Tab:
      return ImGuiKey_Tab;
    case K::Left:
      return ImGuiKey_LeftArrow;
    case K::Right:
      return ImGuiKey_RightArrow;
    case K::Up:
      return ImGuiKey_UpArrow;
    case K::Down:
      return ImGuiKey_DownArrow;
    case K::PageUp:
      return ImGuiKey_PageUp;
    case K::PageDown:
      return ImGuiKey_PageDown;
    case K::Home:
      return ImGuiKey_Home;
    case K::End:
      return ImGuiKey_End;
    case K::Insert:
      return ImGuiKey_Insert;
    case K::Delete:
      return ImGuiKey_Delete;
    case K::Backspace:
      return ImGuiKey_Backspace;
    case K::Space:
      return ImGuiKey_Space;
    case K::Enter:
      return ImGuiKey_Enter;
    case K::Escape:
      return ImGuiKey_Escape;
    case K::A:
      return ImGuiKey_A;
    case K::C:
      return ImGuiKey_C;
    case K::V:
      return ImGuiKey_V;
    case K::X:
      return ImGuiKey_X;
    case K::Y:
      return ImGuiKey_Y;
    case K::Z:
      return ImGuiKey_Z;
    default:
      return ImGuiKey_None;
  }
}

void start_input(ImGuiIO&) {}

void send_mouse_position(ImGuiIO& io, ImVec2 at) {
  io.AddMousePosEvent(at.x, at.y);
}

void send_button(ImGuiIO& io, int index, bool down) {
  io.AddMouseButtonEvent(index, down);
}

void send_wheel(ImGuiIO& io, bool vertical, float delta) {
  io.AddMouseWheelEvent(vertical ? 0.0f : delta, vertical ? delta : 0.0f);
}

void send_key(ImGuiIO& io, const compat::Input& key) {
  io.AddKeyEvent(mod_ctrl, key.control);
  io.AddKeyEvent(mod_shift, key.shift);
  io.AddKeyEvent(mod_alt, key.alt);
  io.AddKeyEvent(mod_super, key.system);
  if (const ImGuiKey named = imgui_key(key.key); named != ImGuiKey_None)
    io.AddKeyEvent(named, key.kind == Kind::key_pressed);
}

void send_focus(ImGuiIO& io, bool focused) {
  io.AddFocusEvent(focused);
}

void before_frame(ImGuiIO&) {}

#else
// ImGui 1.86: input written into ImGuiIO, which the next frame reads. A press and its release can
// arrive within one frame: the press is latched so ImGui still sees the button down for one frame
// and registers the click.
struct LegacyButtons {
  std::array<bool, 3> down{}, pressed{};  // left, right, middle
};
LegacyButtons legacy_buttons;  // one glue a program, as ImGui has one context

void start_input(ImGuiIO& io) {
  legacy_buttons = {};
  // ImGui's keys as indices into io.KeysDown, which holds SFML's key codes.
  using K = sf::Keyboard::Key;
  io.KeyMap[ImGuiKey_Tab] = int(K::Tab);
  io.KeyMap[ImGuiKey_LeftArrow] = int(K::Left);
  io.KeyMap[ImGuiKey_RightArrow] = int(K::Right);
  io.KeyMap[ImGuiKey_UpArrow] = int(K::Up);
  io.KeyMap[ImGuiKey_DownArrow] = int(K::Down);
  io.KeyMap[ImGuiKey_PageUp] = int(K::PageUp);
  io.KeyMap[ImGuiKey_PageDown] = int(K::PageDown);
  io.KeyMap[ImGuiKey_Home] = int(K::Home);
  io.KeyMap[ImGuiKey_End] = int(K::End);
  io.KeyMap[ImGuiKey_Insert] = int(K::Insert);
  io.KeyMap[ImGuiKey_Delete] = int(K::Delete);
  io.KeyMap[ImGuiKey_Backspace] = int(K::Backspace);
  io.KeyMap[ImGuiKey_Space] = int(K::Space);
  io.KeyMap[ImGuiKey_Enter] = int(K::Enter);
  io.KeyMap[ImGuiKey_Escape] = int(K::Escape);
  io.KeyMap[ImGuiKey_KeyPadEnter] = int(K::Enter);
  io.KeyMap[ImGuiKey_A] = int(K::A);
  io.KeyMap[ImGuiKey_C] = int(K::C);
  io.KeyMap[ImGuiKey_V] = int(K::V);
  io.KeyMap[ImGuiKey_X] = int(K::X);
  io.KeyMap[ImGuiKey_Y] = int(K::Y);
  io.KeyMap[ImGuiKey_Z] = int(K::Z);
}

void send_mouse_position(ImGuiIO& io, ImVec2 at) {
  io.MousePos = at;
}

void send_button(ImGuiIO&, int index, bool down) {
  legacy_buttons.down[std::size_t(index)] = down;
  if (down) legacy_buttons.pressed[std::size_t(index)] = true;
}

void send_wheel(ImGuiIO& io, bool vertical, float delta) {
  (vertical ? io.MouseWheel : io.MouseWheelH) += delta;
}

void send_key(ImGuiIO& io, const compat::Input& key) {
  const int code = int(key.key);
  if (code >= 0 && code < int(sf::Keyboard::KeyCount))
    io.KeysDown[code] = key.kind == Kind::key_pressed;
  io.KeyCtrl = key.control;
  io.KeyShift = key.shift;
  io.KeyAlt = key.alt;
  io.KeySuper = key.system;
}

void send_focus(ImGuiIO&, bool focused) {
  if (!focused) legacy_buttons.down.fill(false);
}

void before_frame(ImGuiIO& io) {
  for (std::size_t i = 0; i < legacy_buttons.down.size(); ++i) {
    io.MouseDown[i] = legacy_buttons.down[i] || legacy_buttons.pressed[i];
    legacy_buttons.pressed[i] = false;
  }
}
#endif

// ImGui writes through what its allocator returns without looking: a null (a limit of `ulimit -v`
// reached while it builds its font atlas) was a segmentation fault or a corrupted heap. Out of
// memory, the program ends here with a message and exit 2 (the kit's code for a limit a run does
// not fit in), before ImGui can touch memory it does not have. No allocation on this path: the
// message is formatted on the stack, and std::_Exit runs no destructor of a half-built window.
void* allocate(std::size_t size, void*) {
  if (void* memory = std::malloc(size)) return memory;
  char line[256];
  std::snprintf(line, sizeof line,
                "springlab-view: out of memory: the window's panel (Dear ImGui) could not get %zu "
                "more bytes; allow the process more memory (ulimit -v, ulimit -d) or make the "
                "window smaller (--size)\n",
                size);
  std::fputs(line, stderr);
  std::_Exit(2);
}

void release(void* memory, void*) {
  std::free(memory);
}

}  // namespace

ImGuiGlue::ImGuiGlue(sf::RenderWindow& window) : window_(window) {
  IMGUI_CHECKVERSION();
  ImGui::SetAllocatorFunctions(allocate, release);  // before the context: it is allocated too
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini left in the student's directory
  io.LogFilename = nullptr;
  start_input(io);
  font_file_ = panel_font();
  if (!font_file_.empty())
    io.Fonts->AddFontFromFileTTF(font_file_.c_str(), font_pixels, nullptr, glyph_ranges);
  else
    io.Fonts->AddFontDefault();
  ImGui::StyleColorsDark();
  ImGui_ImplOpenGL2_Init();
}

ImGuiGlue::~ImGuiGlue() {
  ImGui_ImplOpenGL2_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiGlue::handle(const compat::Input& event) {
  ImGuiIO& io = ImGui::GetIO();
  const ImVec2 at(float(event.position.x), float(event.position.y));
  switch (event.kind) {
    case Kind::mouse_moved:
      send_mouse_position(io, at);
      break;
    case Kind::button_pressed:
    case Kind::button_released: {
      const int index = button_index(event.button);
      if (index < 0) break;
      send_mouse_position(io, at);
      send_button(io, index, event.kind == Kind::button_pressed);
      break;
    }
    case Kind::wheel:
      send_wheel(io, event.vertical, event.delta);
      break;
    case Kind::key_pressed:
    case Kind::key_released:
      send_key(io, event);
      break;
    case Kind::text:
      // Control characters (backspace, enter, tab) reach ImGui as keys, not as text.
      if (event.character >= 0x20 && event.character != 0x7F)
        io.AddInputCharacter(unsigned(event.character));
      break;
    case Kind::focus_lost:
    case Kind::focus_gained:
      send_focus(io, event.kind == Kind::focus_gained);
      break;
    case Kind::mouse_left:
      send_mouse_position(io, ImVec2(-FLT_MAX, -FLT_MAX));
      break;
    default:
      break;
  }
}

void ImGuiGlue::new_frame(float seconds) {
  ImGuiIO& io = ImGui::GetIO();
  const sf::Vector2u size = window_.getSize();
  io.DisplaySize = ImVec2(float(size.x), float(size.y));
  io.DeltaTime = seconds > 0.0f ? seconds : 1.0f / 60.0f;
  before_frame(io);
  ImGui_ImplOpenGL2_NewFrame();
  ImGui::NewFrame();
}

void ImGuiGlue::render() {
  ImGui::Render();
  // SFML and ImGui share the GL context: each must find the states it set up (stack.md).
  window_.resetGLStates();
  ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
  window_.resetGLStates();
}

bool ImGuiGlue::wants_mouse() const {
  return ImGui::GetIO().WantCaptureMouse;
}

bool ImGuiGlue::wants_keyboard() const {
  return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace springlab::view
