#include "gui/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace springlab::view {

bool Viewport::contains(sf::Vector2f point) const {
  return point.x >= left && point.x < left + width && point.y >= top && point.y < top + height;
}

void Camera::fit(const Vectors& positions, double spacing) {
  Vec2 low = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 high = -low;
  for (Eigen::Index i = 0; i < positions.cols(); ++i) {
    if (!positions.col(i).allFinite()) continue;
    low = low.cwiseMin(positions.col(i));
    high = high.cwiseMax(positions.col(i));
  }
  if (!(low.array() <= high.array()).all()) return;  // nothing finite to show
  // A margin of a grid spacing (at least a quarter of the size) leaves room for the motion.
  const Vec2 size = high - low;
  const double margin = std::max(spacing, 0.25 * size.maxCoeff());
  centre_ = (low + high) / 2;
  scale_ = std::min(viewport_.width / (size.x() + 2 * margin),
                    viewport_.height / (size.y() + 2 * margin));
}

sf::Vector2f Camera::to_screen(const Vec2& world) const {
  const sf::Vector2f middle = viewport_.centre();
  return {middle.x + static_cast<float>((world.x() - centre_.x()) * scale_),
          middle.y - static_cast<float>((world.y() - centre_.y()) * scale_)};
}

Vec2 Camera::to_world(sf::Vector2f screen) const {
  const sf::Vector2f middle = viewport_.centre();
  return centre_ + Vec2(screen.x - middle.x, middle.y - screen.y) / scale_;
}

void Camera::zoom(double factor, sf::Vector2f fixed) {
  const Vec2 before = to_world(fixed);
  scale_ = std::clamp(scale_ * factor, 1e-6, 1e9);
  centre_ += before - to_world(fixed);
}

void Camera::pan(sf::Vector2f pixels) {
  centre_ -= Vec2(pixels.x, -pixels.y) / scale_;
}

}  // namespace springlab::view
