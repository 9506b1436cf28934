#include "gui/pixel_canvas.hpp"

#include <SFML/Graphics/Sprite.hpp>

#include <algorithm>
#include <cmath>

namespace springlab::view {

void PixelCanvas::begin(const Viewport& area) {
  width_ = std::max(1L, std::lround(area.width));
  height_ = std::max(1L, std::lround(area.height));
  origin_ = {area.left, area.top};
  pixels_.assign(std::size_t(width_ * height_ * 4), 0);
}

void PixelCanvas::put(long x, long y, sf::Color c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  sf::Uint8* p = &pixels_[std::size_t((y * width_ + x) * 4)];
  p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
}

void PixelCanvas::line(sf::Vector2f a, sf::Vector2f b, sf::Color c) {
  a -= origin_;
  b -= origin_;
  // A line far outside (a diverging run) is not walked pixel by pixel.
  const float reach = float(width_ + height_);
  if (std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y)}) > 4 * reach) return;
  const float steps = std::max({std::abs(b.x - a.x), std::abs(b.y - a.y), 1.0f});
  const sf::Vector2f step = (b - a) / steps;
  sf::Vector2f at = a;
  for (long k = 0; k <= long(steps); ++k, at += step)
    put(std::lround(at.x), std::lround(at.y), c);
}

void PixelCanvas::square(sf::Vector2f centre, float half, sf::Color c) {
  centre -= origin_;
  if (std::abs(centre.x) > 1e6f || std::abs(centre.y) > 1e6f) return;
  const long x0 = std::lround(centre.x - half), x1 = std::lround(centre.x + half);
  const long y0 = std::lround(centre.y - half), y1 = std::lround(centre.y + half);
  for (long y = y0; y <= y1; ++y)
    for (long x = x0; x <= x1; ++x)
      put(x, y, c);
}

void PixelCanvas::draw(sf::RenderTarget& target) {
  const sf::Vector2u size{unsigned(width_), unsigned(height_)};
  if (texture_.getSize() != size) texture_.create(size.x, size.y);
  texture_.update(pixels_.data());
  sf::Sprite sprite(texture_);
  sprite.setPosition(origin_);
  target.draw(sprite);
}

}  // namespace springlab::view
