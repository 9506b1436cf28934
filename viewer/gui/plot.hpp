// A small line plot for the panel: several series over the same samples, scaled to fit, with a
// legend that gives each series' latest value. (ImGui 1.86's PlotLines draws one series only.)
#pragma once

#include "gui/parameter_widgets.hpp"

#include <imgui.h>

#include <initializer_list>
#include <vector>

namespace springlab::view {

struct Series {
  const char* name;
  const std::vector<float>* values;
  ImU32 colour;
};

/// The colour of a plot's frame.
struct PlotBackground {
  unsigned char r, g, b;
};
inline constexpr PlotBackground plot_background{16, 18, 24};

/// Draws the series and the legend; returns the plot's frame, which the caller fills with
/// plot_background before ImGui draws (software OpenGL fills an opaque rectangle far faster than
/// ImGui's blended one).
WidgetRect plot(const char* id, const char* unit, std::initializer_list<Series> series,
                float height);

}  // namespace springlab::view
