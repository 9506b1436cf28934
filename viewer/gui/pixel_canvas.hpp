// Lines and squares drawn into memory, then shown as one texture. Software OpenGL (Mesa's
// llvmpipe, as under Xvfb) pays per primitive: 40,000 spring lines cost more than a frame at
// 60 frames/s, while writing their few pixels here and uploading one image costs a few ms.
// The picture covers only the rectangle asked for (what the scene occupies, inside the
// viewport): clearing, uploading and blending the empty rest of the viewport would cost as much
// again on a 100×100 fabric.
#pragma once

#include "gui/camera.hpp"

#include <SFML/Graphics/Color.hpp>
#include <SFML/Graphics/RenderTarget.hpp>
#include <SFML/Graphics/Texture.hpp>

#include <cstdint>
#include <vector>

namespace springlab::view {

class PixelCanvas {
 public:
  /// A pixel as the texture stores it: the bytes r, g, b, a in memory order.
  static std::uint32_t packed(sf::Color c);

  /// Starts a transparent picture of `area` (window pixels, rounded out to whole pixels).
  void begin(const Viewport& area);
  /// A one-pixel line from a to b (window pixels); parts outside the picture are skipped.
  void line(sf::Vector2f a, sf::Vector2f b, std::uint32_t c);
  /// A filled square of half-width `half` pixels around `centre`.
  void square(sf::Vector2f centre, float half, std::uint32_t c);
  /// Shows the picture where begin() put it.
  void draw(sf::RenderTarget& target);

 private:
  void clipped_line(float x0, float y0, float x1, float y1, std::uint32_t c);

  std::vector<std::uint32_t> pixels_;  // row by row from the top
  long width_ = 0, height_ = 0;
  sf::Vector2f origin_;  // the picture's top-left corner in the window
  sf::Texture texture_;
};

}  // namespace springlab::view
