// Sliders for the scene's parameters, generated from for_each_field (parameters.hpp): every
// numeric field gets a slider labelled with its key and unit, a tooltip with its meaning and
// allowed range, and typed values (Ctrl+click) are checked against that range. A field added to
// SceneParameters appears here with no change to the viewer.
#pragma once

#include "springlab/parameters.hpp"

#include <map>
#include <string>
#include <string_view>

namespace springlab::view {

/// Where a widget was drawn, in window pixels (the tests click on them).
struct WidgetRect {
  float left = 0, top = 0, right = 0, bottom = 0;
};

class ParameterWidgets {
 public:
  /// Draws the widgets of every field except `step` and those the panel shows elsewhere,
  /// grouped by the prefix of their key ("structural", "shear", …). Ranges come from `loaded`,
  /// the scene as loaded, so they stay put while a slider moves. Returns true when a value
  /// changed and the scene should be rebuilt.
  bool draw(SceneParameters& p, const SceneParameters& loaded);
  /// The one field `key` (e.g. "step"), drawn where the caller is; true when it changed.
  bool draw_field(SceneParameters& p, const SceneParameters& loaded, std::string_view key);

  /// The rectangle of field `key`'s widget in the last frame it was drawn.
  const std::map<std::string, WidgetRect, std::less<>>& rects() const { return rects_; }

 private:
  template <class T>
  bool widget(const FieldInfo& info, T& value, const T& loaded);

  std::map<std::string, WidgetRect, std::less<>> rects_;
  std::map<std::string, std::string, std::less<>> errors_;  // a typed value out of range
};

}  // namespace springlab::view
