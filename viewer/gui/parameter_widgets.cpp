#include "gui/parameter_widgets.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <type_traits>
#include <vector>

namespace springlab::view {
namespace {

// Fields with a control of their own (integrator, step), or no meaning in a window that runs
// until paused (duration), or not numbers (name).
const std::set<std::string_view> shown_elsewhere = {"name", "task", "integrator", "step",
                                                    "duration"};

std::string group_of(std::string_view key) {
  const auto dot = key.find('.');
  return dot == std::string_view::npos ? std::string("scene") : std::string(key.substr(0, dot));
}

std::string label_of(const FieldInfo& info) {
  std::string label(info.key);
  if (!info.unit.empty()) label += " [" + std::string(info.unit) + "]";
  return label;
}

// Slider ends for a real field: a logarithmic span around its value as loaded when it is
// positive, the field's own range when that is narrow, otherwise a span around the value.
struct Span {
  double low, high;
  bool logarithmic;
};

Span span_of(const Range& range, double loaded) {
  if (loaded > 0 && range.min >= 0) {
    const double low = range.min_open ? std::max(loaded / 100, range.min) : range.min;
    return {low, std::min(loaded * 100, range.max), true};
  }
  if (range.max - range.min <= 1000) return {range.min, range.max, false};
  const double half = std::max(2 * std::abs(loaded), 1.0);
  return {std::max(range.min, loaded - half), std::min(range.max, loaded + half), false};
}

}  // namespace

template <class T>
bool ParameterWidgets::widget(const FieldInfo& info, T& value, const T& loaded) {
  // Text fields (names, particle sets) have no slider: pins are set by clicking particles.
  if constexpr (std::is_same_v<T, std::string>) return false;
  const std::string key(info.key);
  const std::string label = label_of(info);
  bool changed = false;
  ImGui::PushID(key.c_str());
  if constexpr (std::is_same_v<T, bool>) {
    changed = ImGui::Checkbox(label.c_str(), &value);
  } else if constexpr (std::is_same_v<T, int>) {
    // Whole numbers rebuild the grid: applied when the slider is let go, not at every pixel.
    int shown = value;
    const int low = int(std::max(info.range.min, -1e9));
    int high = int(std::min(info.range.max, std::max(10.0 * loaded, 100.0)));
    ImGui::SliderInt(label.c_str(), &shown, low, high);
    if (shown != value) {
      if (info.range.contains(shown)) {
        value = shown;
        errors_.erase(key);
      } else {
        errors_[key] = info.range.describe(info.key, info.unit);
      }
    }
    changed = ImGui::IsItemDeactivatedAfterEdit();
  } else if constexpr (std::is_same_v<T, double>) {
    const Span span = span_of(info.range, loaded);
    double shown = value;
    const ImGuiSliderFlags flags = span.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
    if (ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &shown, &span.low, &span.high,
                            "%.4g", flags)) {
      if (info.range.contains(shown)) {
        value = shown;
        errors_.erase(key);
        changed = true;
      } else {
        errors_[key] = info.range.describe(info.key, info.unit);
      }
    }
  }
  if (ImGui::IsItemHovered() && !info.meaning.empty())
    ImGui::SetTooltip("%s\nallowed: %s\nCtrl+click to type a value",
                      std::string(info.meaning).c_str(),
                      info.range.describe(info.key, info.unit).c_str());
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  rects_[key] = {min.x, min.y, max.x, max.y};
  if (const auto error = errors_.find(key); error != errors_.end())
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "not applied: %s", error->second.c_str());
  ImGui::PopID();
  return changed;
}

bool ParameterWidgets::draw_field(SceneParameters& p, const SceneParameters& loaded,
                                  std::string_view key) {
  bool changed = false;
  // Walk both structs in step: the loaded value of each field sets its slider's ends.
  std::vector<const void*> loaded_values;
  for_each_field(loaded, [&](const FieldInfo&, const auto& v) { loaded_values.push_back(&v); });
  std::size_t index = 0;
  for_each_field(p, [&](const FieldInfo& info, auto& value) {
    using T = std::decay_t<decltype(value)>;
    const T& before = *static_cast<const T*>(loaded_values[index++]);
    if (info.key == key) changed = widget(info, value, before) || changed;
  });
  return changed;
}

bool ParameterWidgets::draw(SceneParameters& p, const SceneParameters& loaded) {
  std::vector<std::string> groups;
  for_each_field(p, [&](const FieldInfo& info, const auto&) {
    const std::string group = group_of(info.key);
    if (!shown_elsewhere.count(info.key) &&
        std::find(groups.begin(), groups.end(), group) == groups.end())
      groups.push_back(group);
  });
  bool changed = false;
  for (const std::string& group : groups) {
    if (!ImGui::TreeNodeEx(group.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
    for_each_field(p, [&](const FieldInfo& info, const auto&) {
      if (group_of(info.key) == group && !shown_elsewhere.count(info.key))
        changed = draw_field(p, loaded, info.key) || changed;
    });
    ImGui::TreePop();
  }
  return changed;
}

}  // namespace springlab::view
