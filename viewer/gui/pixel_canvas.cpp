#include "gui/pixel_canvas.hpp"

#include "gui/sfml_compat.hpp"

#include <SFML/Graphics/Sprite.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace springlab::view {

std::uint32_t PixelCanvas::packed(sf::Color c) {
  const std::uint8_t bytes[4] = {c.r, c.g, c.b, c.a};
  std::uint32_t pixel;
  std::memcpy(&pixel, bytes, sizeof pixel);
  return pixel;
}

void PixelCanvas::begin(const Viewport& area) {
  const float left = std::floor(area.left), top = std::floor(area.top);
  width_ = std::max(1L, long(std::ceil(area.left + area.width) - left));
  height_ = std::max(1L, long(std::ceil(area.top + area.height) - top));
  origin_ = {left, top};
  pixels_.assign(std::size_t(width_ * height_), 0u);  // no reallocation once it has grown
}

void PixelCanvas::line(sf::Vector2f a, sf::Vector2f b, std::uint32_t c) {
  a -= origin_;
  b -= origin_;
  const float right = float(width_ - 1), bottom = float(height_ - 1);
  // Wholly outside: nothing to walk. Within: every pixel is too, so no test per pixel.
  if (std::max(a.x, b.x) < -0.5f || std::min(a.x, b.x) > right + 0.5f ||
      std::max(a.y, b.y) < -0.5f || std::min(a.y, b.y) > bottom + 0.5f)
    return;
  if (std::min({a.x, b.x, a.y, b.y}) < 0.0f || std::max(a.x, b.x) > right ||
      std::max(a.y, b.y) > bottom)
    return clipped_line(a.x, a.y, b.x, b.y, c);
  // A DDA in 16.16 fixed point: the pixel nearest each of max(|dx|, |dy|) + 1 evenly spaced
  // points, as rounding floats would give, without a rounding call per pixel.
  const float steps = std::max({std::abs(b.x - a.x), std::abs(b.y - a.y), 1.0f});
  const long n = long(steps);
  constexpr float one = 65536.0f;
  std::int32_t x = std::int32_t((a.x + 0.5f) * one), y = std::int32_t((a.y + 0.5f) * one);
  const std::int32_t dx = std::int32_t((b.x - a.x) / steps * one);
  const std::int32_t dy = std::int32_t((b.y - a.y) / steps * one);
  std::uint32_t* const p = pixels_.data();
  for (long k = 0; k <= n; ++k, x += dx, y += dy)
    p[long(y >> 16) * width_ + long(x >> 16)] = c;
}

void PixelCanvas::clipped_line(float x0, float y0, float x1, float y1, std::uint32_t c) {
  // A line far outside (a diverging run) is not walked pixel by pixel.
  const float reach = 4.0f * float(width_ + height_);
  if (std::max({std::abs(x0), std::abs(y0), std::abs(x1), std::abs(y1)}) > reach) return;
  const float steps = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1.0f});
  const float sx = (x1 - x0) / steps, sy = (y1 - y0) / steps;
  for (long k = 0; k <= long(steps); ++k) {
    const long x = std::lround(x0 + float(k) * sx), y = std::lround(y0 + float(k) * sy);
    if (x >= 0 && y >= 0 && x < width_ && y < height_) pixels_[std::size_t(y * width_ + x)] = c;
  }
}

void PixelCanvas::square(sf::Vector2f centre, float half, std::uint32_t c) {
  centre -= origin_;
  if (std::abs(centre.x) > 1e6f || std::abs(centre.y) > 1e6f) return;
  const long x0 = std::max(0L, std::lround(centre.x - half));
  const long x1 = std::min(width_ - 1, std::lround(centre.x + half));
  const long y0 = std::max(0L, std::lround(centre.y - half));
  const long y1 = std::min(height_ - 1, std::lround(centre.y + half));
  if (x0 > x1) return;
  for (long y = y0; y <= y1; ++y)
    std::fill(&pixels_[std::size_t(y * width_ + x0)], &pixels_[std::size_t(y * width_ + x1)] + 1,
              c);
}

void PixelCanvas::draw(sf::RenderTarget& target) {
  const sf::Vector2u size{unsigned(width_), unsigned(height_)};
  // Grown, never shrunk: a texture made for each new size would cost more than the upload.
  const sf::Vector2u had = texture_.getSize();
  if ((had.x < size.x || had.y < size.y) &&
      !compat::resize(texture_, {std::max(size.x, had.x), std::max(size.y, had.y)}))
    return;  // no texture that large: the picture is not shown
  compat::update(texture_, reinterpret_cast<const std::uint8_t*>(pixels_.data()), size);
  sf::Sprite sprite(texture_, compat::int_rect(0, 0, int(size.x), int(size.y)));
  sprite.setPosition(origin_);
  target.draw(sprite);
}

}  // namespace springlab::view
