// A small line plot for the panel: several series over the same samples, scaled to fit, with a
// legend that gives each series' latest value. (ImGui 1.86's PlotLines draws one series only.)
#pragma once

#include <imgui.h>

#include <initializer_list>
#include <vector>

namespace springlab::view {

struct Series {
  const char* name;
  const std::vector<float>* values;
  ImU32 colour;
};

void plot(const char* id, const char* unit, std::initializer_list<Series> series, float height);

}  // namespace springlab::view
