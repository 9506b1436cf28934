// The one place where world coordinates (metres, y up) become screen pixels (y down), and back.
#pragma once

#include "springlab/types.hpp"

#include <SFML/System/Vector2.hpp>

namespace springlab::view {

/// A rectangle of the window, in pixels.
struct Viewport {
  float left = 0.0f, top = 0.0f, width = 1.0f, height = 1.0f;
  bool contains(sf::Vector2f point) const;
  sf::Vector2f centre() const { return {left + width / 2, top + height / 2}; }
};

class Camera {
 public:
  /// Shows every finite position with a margin, centred in the viewport; the camera then
  /// follows (keep_in_view) until the user pans or zooms.
  void fit(const Vectors& positions, double spacing);
  /// While the camera follows: zooms out (never in) so that every finite position stays at
  /// least a spacing inside the viewport, a fabric sagging under gravity included.
  void keep_in_view(const Vectors& positions, double spacing);
  bool follows() const { return follows_; }
  void set_viewport(const Viewport& viewport) { viewport_ = viewport; }
  const Viewport& viewport() const { return viewport_; }

  sf::Vector2f to_screen(const Vec2& world) const;
  Vec2 to_world(sf::Vector2f screen) const;
  /// Zooms by `factor` keeping the world point under `fixed` where it is.
  void zoom(double factor, sf::Vector2f fixed);
  void pan(sf::Vector2f pixels);
  double pixels_per_metre() const { return scale_; }

 private:
  void show(const Vec2& low, const Vec2& high);  // the world's box low..high fills the viewport

  Viewport viewport_;
  Vec2 centre_{0.0, 0.0};  // world point at the viewport's centre, m
  double scale_ = 100.0;   // pixels per metre
  bool follows_ = false;   // since the last fit, no pan or zoom by the user
};

}  // namespace springlab::view
