// Lines and squares drawn into memory, then shown as one texture. Software OpenGL (Mesa's
// llvmpipe, as under Xvfb) pays per primitive: 40,000 spring lines cost more than a frame at
// 60 frames/s, while writing their few pixels here and uploading one image costs a few ms.
#pragma once

#include "gui/camera.hpp"

#include <SFML/Graphics/Color.hpp>
#include <SFML/Graphics/RenderTarget.hpp>
#include <SFML/Graphics/Texture.hpp>

#include <vector>

namespace springlab::view {

class PixelCanvas {
 public:
  /// Starts a transparent picture of the viewport `area`.
  void begin(const Viewport& area);
  /// A one-pixel line from a to b (window pixels); parts outside the viewport are skipped.
  void line(sf::Vector2f a, sf::Vector2f b, sf::Color c);
  /// A filled square of half-width `half` pixels around `centre`.
  void square(sf::Vector2f centre, float half, sf::Color c);
  /// Shows the picture over the viewport.
  void draw(sf::RenderTarget& target);

 private:
  void put(long x, long y, sf::Color c);

  std::vector<sf::Uint8> pixels_;  // RGBA, row by row from the top
  long width_ = 0, height_ = 0;
  sf::Vector2f origin_;  // the viewport's top-left corner in the window
  sf::Texture texture_;
};

}  // namespace springlab::view
