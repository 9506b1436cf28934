#include "gui/sfml_compat.hpp"

#include <SFML/Config.hpp>

namespace springlab::view::compat {

using Kind = Input::Kind;

#if SFML_VERSION_MAJOR >= 3

namespace {

template <class KeyEvent>
void read_key(const KeyEvent& event, Input& in) {
  in.key = event.code;
  in.alt = event.alt;
  in.control = event.control;
  in.shift = event.shift;
  in.system = event.system;
}

template <class KeyEvent>
KeyEvent key_event(const Input& in) {
  KeyEvent event;
  event.code = in.key;
  event.scancode = sf::Keyboard::Scancode::Unknown;
  event.alt = in.alt;
  event.control = in.control;
  event.shift = in.shift;
  event.system = in.system;
  return event;
}

}  // namespace

Input read(const sf::Event& event) {
  using E = sf::Event;
  Input in;
  if (event.is<E::Closed>()) {
    in.kind = Kind::closed;
  } else if (const auto* resized = event.getIf<E::Resized>()) {
    in.kind = Kind::resized;
    in.size = resized->size;
  } else if (event.is<E::FocusLost>()) {
    in.kind = Kind::focus_lost;
  } else if (event.is<E::FocusGained>()) {
    in.kind = Kind::focus_gained;
  } else if (event.is<E::MouseLeft>()) {
    in.kind = Kind::mouse_left;
  } else if (const auto* moved = event.getIf<E::MouseMoved>()) {
    in.kind = Kind::mouse_moved;
    in.position = moved->position;
  } else if (const auto* pressed = event.getIf<E::MouseButtonPressed>()) {
    in.kind = Kind::button_pressed;
    in.button = pressed->button;
    in.position = pressed->position;
  } else if (const auto* released = event.getIf<E::MouseButtonReleased>()) {
    in.kind = Kind::button_released;
    in.button = released->button;
    in.position = released->position;
  } else if (const auto* wheel = event.getIf<E::MouseWheelScrolled>()) {
    in.kind = Kind::wheel;
    in.vertical = wheel->wheel == sf::Mouse::Wheel::Vertical;
    in.delta = wheel->delta;
    in.position = wheel->position;
  } else if (const auto* key = event.getIf<E::KeyPressed>()) {
    in.kind = Kind::key_pressed;
    read_key(*key, in);
  } else if (const auto* key_up = event.getIf<E::KeyReleased>()) {
    in.kind = Kind::key_released;
    read_key(*key_up, in);
  } else if (const auto* text = event.getIf<E::TextEntered>()) {
    in.kind = Kind::text;
    in.character = text->unicode;
  }
  return in;
}

sf::Event event_of(const Input& in) {
  using E = sf::Event;
  switch (in.kind) {
    case Kind::closed:
      return E::Closed{};
    case Kind::resized:
      return E::Resized{in.size};
    case Kind::focus_lost:
      return E::FocusLost{};
    case Kind::focus_gained:
      return E::FocusGained{};
    case Kind::mouse_left:
      return E::MouseLeft{};
    case Kind::mouse_moved:
      return E::MouseMoved{in.position};
    case Kind::button_pressed:
      return E::MouseButtonPressed{in.button, in.position};
    case Kind::button_released:
      return E::MouseButtonReleased{in.button, in.position};
    case Kind::wheel:
      return E::MouseWheelScrolled{
          in.vertical ? sf::Mouse::Wheel::Vertical : sf::Mouse::Wheel::Horizontal, in.delta,
          in.position};
    case Kind::key_pressed:
      return key_event<E::KeyPressed>(in);
    case Kind::key_released:
      return key_event<E::KeyReleased>(in);
    case Kind::text:
      return E::TextEntered{in.character};
    case Kind::other:
      break;
  }
  return E::MouseEntered{};  // one the viewer ignores
}

std::optional<sf::Event> poll(sf::Window& window) {
  return window.pollEvent();
}

sf::VideoMode video_mode(sf::Vector2u size) {
  return sf::VideoMode(size);
}

sf::FloatRect float_rect(float left, float top, float width, float height) {
  return {{left, top}, {width, height}};
}

sf::IntRect int_rect(int left, int top, int width, int height) {
  return {{left, top}, {width, height}};
}

bool resize(sf::Texture& texture, sf::Vector2u size) {
  return texture.resize(size);
}

void update(sf::Texture& texture, const std::uint8_t* pixels, sf::Vector2u size) {
  texture.update(pixels, size, {0, 0});
}

sf::Color pixel(const sf::Image& image, unsigned x, unsigned y) {
  return image.getPixel({x, y});
}

#else  // SFML 2.5 and 2.6

Input read(const sf::Event& event) {
  Input in;
  switch (event.type) {
    case sf::Event::Closed:
      in.kind = Kind::closed;
      break;
    case sf::Event::Resized:
      in.kind = Kind::resized;
      in.size = {event.size.width, event.size.height};
      break;
    case sf::Event::LostFocus:
      in.kind = Kind::focus_lost;
      break;
    case sf::Event::GainedFocus:
      in.kind = Kind::focus_gained;
      break;
    case sf::Event::MouseLeft:
      in.kind = Kind::mouse_left;
      break;
    case sf::Event::MouseMoved:
      in.kind = Kind::mouse_moved;
      in.position = {event.mouseMove.x, event.mouseMove.y};
      break;
    case sf::Event::MouseButtonPressed:
    case sf::Event::MouseButtonReleased:
      in.kind = event.type == sf::Event::MouseButtonPressed ? Kind::button_pressed
                                                            : Kind::button_released;
      in.button = event.mouseButton.button;
      in.position = {event.mouseButton.x, event.mouseButton.y};
      break;
    case sf::Event::MouseWheelScrolled:
      in.kind = Kind::wheel;
      in.vertical = event.mouseWheelScroll.wheel == sf::Mouse::VerticalWheel;
      in.delta = event.mouseWheelScroll.delta;
      in.position = {event.mouseWheelScroll.x, event.mouseWheelScroll.y};
      break;
    case sf::Event::KeyPressed:
    case sf::Event::KeyReleased:
      in.kind = event.type == sf::Event::KeyPressed ? Kind::key_pressed : Kind::key_released;
      in.key = event.key.code;
      in.alt = event.key.alt;
      in.control = event.key.control;
      in.shift = event.key.shift;
      in.system = event.key.system;
      break;
    case sf::Event::TextEntered:
      in.kind = Kind::text;
      in.character = char32_t(event.text.unicode);
      break;
    default:
      break;
  }
  return in;
}

sf::Event event_of(const Input& in) {
  sf::Event event{};  // SFML 2.6's key events add a scancode: left zero here
  switch (in.kind) {
    case Kind::closed:
      event.type = sf::Event::Closed;
      break;
    case Kind::resized:
      event.type = sf::Event::Resized;
      event.size.width = in.size.x;
      event.size.height = in.size.y;
      break;
    case Kind::focus_lost:
      event.type = sf::Event::LostFocus;
      break;
    case Kind::focus_gained:
      event.type = sf::Event::GainedFocus;
      break;
    case Kind::mouse_left:
      event.type = sf::Event::MouseLeft;
      break;
    case Kind::mouse_moved:
      event.type = sf::Event::MouseMoved;
      event.mouseMove.x = in.position.x;
      event.mouseMove.y = in.position.y;
      break;
    case Kind::button_pressed:
    case Kind::button_released:
      event.type = in.kind == Kind::button_pressed ? sf::Event::MouseButtonPressed
                                                   : sf::Event::MouseButtonReleased;
      event.mouseButton.button = in.button;
      event.mouseButton.x = in.position.x;
      event.mouseButton.y = in.position.y;
      break;
    case Kind::wheel:
      event.type = sf::Event::MouseWheelScrolled;
      event.mouseWheelScroll.wheel =
          in.vertical ? sf::Mouse::VerticalWheel : sf::Mouse::HorizontalWheel;
      event.mouseWheelScroll.delta = in.delta;
      event.mouseWheelScroll.x = in.position.x;
      event.mouseWheelScroll.y = in.position.y;
      break;
    case Kind::key_pressed:
    case Kind::key_released:
      event.type = in.kind == Kind::key_pressed ? sf::Event::KeyPressed : sf::Event::KeyReleased;
      event.key.code = in.key;
      event.key.alt = in.alt;
      event.key.control = in.control;
      event.key.shift = in.shift;
      event.key.system = in.system;
      break;
    case Kind::text:
      event.type = sf::Event::TextEntered;
      event.text.unicode = sf::Uint32(in.character);
      break;
    case Kind::other:
      event.type = sf::Event::MouseEntered;  // one the viewer ignores
      break;
  }
  return event;
}

std::optional<sf::Event> poll(sf::Window& window) {
  sf::Event event;
  if (window.pollEvent(event)) return event;
  return std::nullopt;
}

sf::VideoMode video_mode(sf::Vector2u size) {
  return sf::VideoMode(size.x, size.y);
}

sf::FloatRect float_rect(float left, float top, float width, float height) {
  return sf::FloatRect(left, top, width, height);
}

sf::IntRect int_rect(int left, int top, int width, int height) {
  return sf::IntRect(left, top, width, height);
}

bool resize(sf::Texture& texture, sf::Vector2u size) {
  return texture.create(size.x, size.y);
}

void update(sf::Texture& texture, const std::uint8_t* pixels, sf::Vector2u size) {
  texture.update(pixels, size.x, size.y, 0, 0);
}

sf::Color pixel(const sf::Image& image, unsigned x, unsigned y) {
  return image.getPixel(x, y);
}

#endif

}  // namespace springlab::view::compat
