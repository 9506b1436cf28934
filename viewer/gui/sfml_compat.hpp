// SFML 2.5 to 3.x from one source. SFML 3 reads events differently (a std::optional of a
// std::variant, read with getIf<>), sizes video modes, rectangles and textures with sf::Vector2,
// and renames a few functions. The viewer reads and makes events only as an Input, and calls
// those few functions only through this header; sfml_compat.cpp holds each version's half.
// Everything else the viewer uses is spelled alike in both: SFML 2's plain enums accept the
// scoped spelling (sf::Keyboard::Key::A, sf::Mouse::Button::Left, sf::PrimitiveType::Triangles),
// and the kit writes std::uint8_t where SFML 2 wrote sf::Uint8.
#pragma once

#include <SFML/Graphics/Color.hpp>
#include <SFML/Graphics/Image.hpp>
#include <SFML/Graphics/Rect.hpp>
#include <SFML/Graphics/Texture.hpp>
#include <SFML/Window/Event.hpp>
#include <SFML/Window/VideoMode.hpp>
#include <SFML/Window/Window.hpp>

#include <cstdint>
#include <optional>

namespace springlab::view::compat {

/// An event as the viewer reads it, whichever SFML made it: its kind, and the fields that kind
/// carries (the others keep their defaults).
struct Input {
  enum class Kind {
    other,  // an event the viewer ignores
    closed,
    resized,
    focus_lost,
    focus_gained,
    mouse_left,
    mouse_moved,
    button_pressed,
    button_released,
    wheel,
    key_pressed,
    key_released,
    text,
  };
  Kind kind = Kind::other;
  sf::Vector2i position;  ///< the mouse, window pixels (mouse_moved, button_*, wheel)
  sf::Vector2u size;      ///< resized: the window's new size, pixels
  sf::Mouse::Button button = sf::Mouse::Button::Left;
  bool vertical = true;  ///< wheel: the vertical wheel, not the horizontal one
  float delta = 0.0f;    ///< wheel: notches turned, positive up or left
  sf::Keyboard::Key key = sf::Keyboard::Key::Unknown;
  bool alt = false, control = false, shift = false, system = false;  ///< key_*: modifiers held
  char32_t character = 0;                                            ///< text: a code point
};

Input read(const sf::Event& event);
/// The event SFML would deliver for `input` (tests and headless runs make events this way).
sf::Event event_of(const Input& input);
/// The window's next waiting event, if any.
std::optional<sf::Event> poll(sf::Window& window);

sf::VideoMode video_mode(sf::Vector2u size);
sf::FloatRect float_rect(float left, float top, float width, float height);
sf::IntRect int_rect(int left, int top, int width, int height);
/// Makes `texture` `size` pixels large (its content undefined); false when it cannot.
[[nodiscard]] bool resize(sf::Texture& texture, sf::Vector2u size);
/// Copies `size` pixels, RGBA bytes row by row, into the texture's top-left corner.
void update(sf::Texture& texture, const std::uint8_t* pixels, sf::Vector2u size);
sf::Color pixel(const sf::Image& image, unsigned x, unsigned y);

}  // namespace springlab::view::compat
