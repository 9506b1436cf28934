#include "gui/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace springlab::view {

bool Viewport::contains(sf::Vector2f point) const {
  return point.x >= left && point.x < left + width && point.y >= top && point.y < top + height;
}

namespace {

// The box around every finite position; empty (low > high) when none is finite.
struct Box {
  Vec2 low = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 high = -Vec2::Constant(std::numeric_limits<double>::infinity());
  bool empty() const { return !(low.array() <= high.array()).all(); }
};

Box bounds(const Vectors& positions) {
  Box box;
  for (Eigen::Index i = 0; i < positions.cols(); ++i) {
    if (!positions.col(i).allFinite()) continue;
    box.low = box.low.cwiseMin(positions.col(i));
    box.high = box.high.cwiseMax(positions.col(i));
  }
  return box;
}

}  // namespace

void Camera::show(const Vec2& low, const Vec2& high) {
  const Vec2 size = high - low;
  centre_ = (low + high) / 2;
  scale_ = std::min(viewport_.width / size.x(), viewport_.height / size.y());
}

void Camera::fit(const Vectors& positions, double spacing) {
  const Box box = bounds(positions);
  if (box.empty()) return;  // nothing finite to show
  // A margin of a grid spacing (at least a quarter of the size) leaves room for the motion.
  const double margin = std::max(spacing, 0.25 * (box.high - box.low).maxCoeff());
  show(box.low - Vec2::Constant(margin), box.high + Vec2::Constant(margin));
  follows_ = true;
}

void Camera::keep_in_view(const Vectors& positions, double spacing) {
  if (!follows_) return;
  const Box box = bounds(positions);
  if (box.empty()) return;
  const Vec2 half(viewport_.width / 2 / scale_, viewport_.height / 2 / scale_);
  const Vec2 shown_low = centre_ - half, shown_high = centre_ + half;
  const Vec2 need_low = box.low - Vec2::Constant(spacing);
  const Vec2 need_high = box.high + Vec2::Constant(spacing);
  if ((need_low.array() >= shown_low.array()).all() &&
      (need_high.array() <= shown_high.array()).all())
    return;
  // Grown by a quarter beyond what is needed, so that a sagging fabric is not followed frame
  // by frame.
  const Vec2 low = need_low.cwiseMin(shown_low), high = need_high.cwiseMax(shown_high);
  const Vec2 grow = 0.125 * (high - low);
  show(low - grow, high + grow);
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
  follows_ = false;
  const Vec2 before = to_world(fixed);
  scale_ = std::clamp(scale_ * factor, 1e-6, 1e9);
  centre_ += before - to_world(fixed);
}

void Camera::pan(sf::Vector2f pixels) {
  follows_ = false;
  centre_ -= Vec2(pixels.x, -pixels.y) / scale_;
}

}  // namespace springlab::view
