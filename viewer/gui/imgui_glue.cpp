#include "gui/imgui_glue.hpp"

#include <imgui.h>
#include <imgui_impl_opengl2.h>

#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace springlab::view {
namespace {

// ImGui's own font lacks the symbols the kit writes (ℓ0, ω, ≈, —); DejaVu has them all.
const char* const font_file = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
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

int button_index(sf::Mouse::Button button) {
  switch (button) {
    case sf::Mouse::Left:
      return 0;
    case sf::Mouse::Right:
      return 1;
    case sf::Mouse::Middle:
      return 2;
    default:
      return -1;
  }
}

void map_keys(ImGuiIO& io) {
  io.KeyMap[ImGuiKey_Tab] = sf::Keyboard::Tab;
  io.KeyMap[ImGuiKey_LeftArrow] = sf::Keyboard::Left;
  io.KeyMap[ImGuiKey_RightArrow] = sf::Keyboard::Right;
  io.KeyMap[ImGuiKey_UpArrow] = sf::Keyboard::Up;
  io.KeyMap[ImGuiKey_DownArrow] = sf::Keyboard::Down;
  io.KeyMap[ImGuiKey_PageUp] = sf::Keyboard::PageUp;
  io.KeyMap[ImGuiKey_PageDown] = sf::Keyboard::PageDown;
  io.KeyMap[ImGuiKey_Home] = sf::Keyboard::Home;
  io.KeyMap[ImGuiKey_End] = sf::Keyboard::End;
  io.KeyMap[ImGuiKey_Insert] = sf::Keyboard::Insert;
  io.KeyMap[ImGuiKey_Delete] = sf::Keyboard::Delete;
  io.KeyMap[ImGuiKey_Backspace] = sf::Keyboard::Backspace;
  io.KeyMap[ImGuiKey_Space] = sf::Keyboard::Space;
  io.KeyMap[ImGuiKey_Enter] = sf::Keyboard::Enter;
  io.KeyMap[ImGuiKey_Escape] = sf::Keyboard::Escape;
  io.KeyMap[ImGuiKey_KeyPadEnter] = sf::Keyboard::Enter;
  io.KeyMap[ImGuiKey_A] = sf::Keyboard::A;
  io.KeyMap[ImGuiKey_C] = sf::Keyboard::C;
  io.KeyMap[ImGuiKey_V] = sf::Keyboard::V;
  io.KeyMap[ImGuiKey_X] = sf::Keyboard::X;
  io.KeyMap[ImGuiKey_Y] = sf::Keyboard::Y;
  io.KeyMap[ImGuiKey_Z] = sf::Keyboard::Z;
}

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

void set_modifiers(ImGuiIO& io, const sf::Event::KeyEvent& key) {
  io.KeyCtrl = key.control;
  io.KeyShift = key.shift;
  io.KeyAlt = key.alt;
  io.KeySuper = key.system;
}

}  // namespace

ImGuiGlue::ImGuiGlue(sf::RenderWindow& window) : window_(window) {
  IMGUI_CHECKVERSION();
  ImGui::SetAllocatorFunctions(allocate, release);  // before the context: it is allocated too
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini left in the student's directory
  io.LogFilename = nullptr;
  map_keys(io);
  if (std::filesystem::exists(font_file))
    io.Fonts->AddFontFromFileTTF(font_file, font_pixels, nullptr, glyph_ranges);
  else
    io.Fonts->AddFontDefault();
  ImGui::StyleColorsDark();
  ImGui_ImplOpenGL2_Init();
}

ImGuiGlue::~ImGuiGlue() {
  ImGui_ImplOpenGL2_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiGlue::handle(const sf::Event& event) {
  ImGuiIO& io = ImGui::GetIO();
  switch (event.type) {
    case sf::Event::MouseMoved:
      io.MousePos = ImVec2(float(event.mouseMove.x), float(event.mouseMove.y));
      break;
    case sf::Event::MouseButtonPressed:
    case sf::Event::MouseButtonReleased: {
      const int index = button_index(event.mouseButton.button);
      if (index < 0) break;
      const bool pressed = event.type == sf::Event::MouseButtonPressed;
      io.MousePos = ImVec2(float(event.mouseButton.x), float(event.mouseButton.y));
      down_[std::size_t(index)] = pressed;
      if (pressed) pressed_[std::size_t(index)] = true;
      break;
    }
    case sf::Event::MouseWheelScrolled:
      if (event.mouseWheelScroll.wheel == sf::Mouse::VerticalWheel)
        io.MouseWheel += event.mouseWheelScroll.delta;
      else
        io.MouseWheelH += event.mouseWheelScroll.delta;
      break;
    case sf::Event::KeyPressed:
    case sf::Event::KeyReleased:
      if (event.key.code >= 0 && event.key.code < sf::Keyboard::KeyCount)
        io.KeysDown[event.key.code] = event.type == sf::Event::KeyPressed;
      set_modifiers(io, event.key);
      break;
    case sf::Event::TextEntered:
      // Control characters (backspace, enter, tab) reach ImGui as keys, not as text.
      if (event.text.unicode >= 0x20 && event.text.unicode != 0x7F)
        io.AddInputCharacter(event.text.unicode);
      break;
    case sf::Event::LostFocus:
      down_.fill(false);
      break;
    case sf::Event::MouseLeft:
      io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
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
  for (std::size_t i = 0; i < buttons; ++i) {
    io.MouseDown[i] = down_[i] || pressed_[i];
    pressed_[i] = false;
  }
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
