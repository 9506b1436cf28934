#include "gui/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace springlab::view {

WidgetRect plot(const char* id, const char* unit, std::initializer_list<Series> series,
                float height) {
  float low = 0.0f, high = 0.0f;  // zero stays in view: an energy is read against it
  std::size_t samples = 0;
  for (const Series& s : series) {
    samples = std::max(samples, s.values->size());
    for (float v : *s.values)
      if (std::isfinite(v)) low = std::min(low, v), high = std::max(high, v);
  }
  if (high - low < 1e-12f) high = low + 1.0f;
  ImGui::PushID(id);
  const float width = ImGui::GetContentRegionAvail().x;
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("plot", ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 far(corner.x + width, corner.y + height);
  const float zero_y = corner.y + height * (high / (high - low));
  draw->AddLine(ImVec2(corner.x, zero_y), ImVec2(far.x, zero_y), IM_COL32(80, 80, 90, 255));
  for (const Series& s : series) {
    const std::vector<float>& v = *s.values;
    std::vector<ImVec2> points;
    points.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i])) continue;
      const float x = corner.x + width * float(i) / float(std::max<std::size_t>(samples - 1, 1));
      points.emplace_back(x, corner.y + height * (high - v[i]) / (high - low));
    }
    // A whole-pixel width lets ImGui anti-alias with its line texture: two triangles a segment
    // rather than six, which software OpenGL sets up one by one (3,000 segments a frame).
    if (points.size() > 1) draw->AddPolyline(points.data(), int(points.size()), s.colour, 0, 2.0f);
  }
  char scale[64];
  std::snprintf(scale, sizeof scale, "%.3g %s", double(high), unit);
  draw->AddText(ImVec2(corner.x + 3, corner.y + 1), IM_COL32(170, 170, 180, 255), scale);
  for (const Series& s : series) {
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(s.colour), "%s %.4g %s", s.name,
                       s.values->empty() ? 0.0 : double(s.values->back()), unit);
    ImGui::SameLine();
  }
  ImGui::NewLine();
  ImGui::PopID();
  return {corner.x, corner.y, far.x, far.y};
}

}  // namespace springlab::view
