#include "gui/panel.hpp"

#include "gui/plot.hpp"
#include "springlab/integrator.hpp"
#include "springlab/scene.hpp"

#include <imgui.h>

#include <SFML/Graphics/Vertex.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>

namespace springlab::view {
namespace {

const ImVec4 warning_colour(1.0f, 0.55f, 0.3f, 1.0f);
const ImVec4 quiet_colour(0.65f, 0.65f, 0.7f, 1.0f);

constexpr double min_factor = 0.01, max_factor = 10.0;  // real-time factor slider
constexpr double min_strain = 0.001, max_strain = 1.0;  // strain drawn at full colour

const char* compare_names[] = {"off", "overlay (reference in blue)", "side by side"};

}  // namespace

void Panel::remember(const std::string& name) {
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  rects_[name] = {min.x, min.y, max.x, max.y};
}

void Panel::remember_background() {
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  const ImVec2 far(at.x + size.x, at.y + size.y);
  backgrounds_.push_back({at.x, at.y, far.x, far.y});
  // The outline ImGui leaves out with the background, as ImGui draws it.
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(at, far);
  draw->AddRect(at, far, ImGui::GetColorU32(ImGuiCol_Border), 0.0f, 0,
                ImGui::GetStyle().WindowBorderSize);
  draw->PopClipRect();
}

void Panel::draw_backgrounds(sf::RenderTarget& target) const {
  // ImGui's window colour over the window's background, as ImGui's blending would give it.
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  const auto over = [&bg](float c, std::uint8_t under) {
    return std::uint8_t(std::lround(255.0f * c * bg.w + float(under) * (1.0f - bg.w)));
  };
  const sf::Color c(over(bg.x, colour::background.r), over(bg.y, colour::background.g),
                    over(bg.z, colour::background.b));
  std::vector<sf::Vertex> triangles;  // two a rectangle (SFML 3 has no quads)
  const auto fill = [&triangles](const WidgetRect& r, sf::Color colour) {
    const sf::Vector2f top_left(r.left, r.top), top_right(r.right, r.top),
        bottom_right(r.right, r.bottom), bottom_left(r.left, r.bottom);
    for (sf::Vector2f corner :
         {top_left, top_right, bottom_right, top_left, bottom_right, bottom_left})
      triangles.push_back({corner, colour});
  };
  for (const WidgetRect& r : backgrounds_)
    fill(r, c);
  // The plots' frames too: a quarter of what ImGui would otherwise fill, blended, each frame.
  for (const WidgetRect& r : plot_frames_)
    fill(r, sf::Color(plot_background.r, plot_background.g, plot_background.b));
  target.draw(triangles.data(), triangles.size(), sf::PrimitiveType::Triangles,
              sf::RenderStates(sf::BlendNone));
}

std::optional<WidgetRect> Panel::rect(const std::string& name) const {
  if (const auto found = rects_.find(name); found != rects_.end()) return found->second;
  if (const auto found = parameters_.rects().find(name); found != parameters_.rects().end())
    return found->second;
  return std::nullopt;
}

PanelRequests Panel::draw(Session& session, ViewSettings& settings, const FrameInfo& frame,
                          const Viewport& scene_area) {
  PanelRequests requests;
  backgrounds_.clear();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x - width, 0));
  ImGui::SetNextWindowSize(ImVec2(width, display.y));
  ImGui::Begin("springlab", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBackground);
  remember_background();
  ImGui::PushItemWidth(-170.0f);  // room for the labels, which carry key and unit
  scene_section(session);
  run_section(session, requests);
  stepping_section(session, frame);
  if (ImGui::CollapsingHeader("Show", ImGuiTreeNodeFlags_DefaultOpen))
    display_section(session, settings);
  if (ImGui::CollapsingHeader("Scene parameters", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextColored(quiet_colour, "Ctrl+click a slider to type a value");
    if (parameters_.draw(session.parameters(), session.loaded_parameters())) session.apply();
  }
  if (ImGui::CollapsingHeader("Particle under the mouse", ImGuiTreeNodeFlags_DefaultOpen))
    particle_section(session, settings, frame);
  ImGui::PopItemWidth();
  ImGui::End();
  plots(session, scene_area);
  banner(session, scene_area);
  return requests;
}

void Panel::scene_section(Session& session) {
  const SceneParameters& p = session.parameters();
  if (ImGui::BeginCombo("scene", session.source().c_str())) {
    for (const std::string& name : task_scene_names())
      if (ImGui::Selectable(name.c_str(), name == session.source())) session.load(name);
    ImGui::EndCombo();
  }
  ImGui::InputTextWithHint("##file", "or a scene file (.toml)", file_.data(), file_.size());
  remember("scene file");
  ImGui::SameLine();
  if (ImGui::Button("Load") && file_[0] != '\0') session.load(file_.data());
  remember("load");

  int code = session.code() == Code::student ? 1 : 0;
  const std::string yours = p.task > 0 ? "yours (task " + std::to_string(p.task) + ")" : "yours";
  ImGui::Text("code:");
  ImGui::SameLine();
  bool changed = ImGui::RadioButton("reference", &code, 0);
  ImGui::SameLine();
  changed = ImGui::RadioButton(yours.c_str(), &code, 1) || changed;
  if (changed) session.set_code(code == 1 ? Code::student : Code::reference);
  remember("code");

  ImGui::BeginDisabled(session.code() != Code::student);
  int compare = int(session.compare());
  if (ImGui::Combo("compare", &compare, compare_names, 3)) session.set_compare(Compare(compare));
  ImGui::EndDisabled();
  if (const std::optional<Comparison> c = session.comparison()) {
    ImGui::TextWrapped("yours %s", comparison_figures(*c).c_str());
    if (!c->remark.empty())
      ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "differs: see the note above the scene");
  }
}

void Panel::run_section(Session& session, PanelRequests& requests) {
  ImGui::Separator();
  if (ImGui::Button(session.running() ? "Pause" : "Run", ImVec2(70, 0)))
    session.set_running(!session.running());
  remember("run");
  ImGui::SameLine();
  if (ImGui::Button("Step")) session.single_step();
  remember("step once");
  ImGui::SameLine();
  if (ImGui::Button("Reset")) session.reset();
  remember("reset");
  ImGui::SameLine();
  if (ImGui::Button("Fit view")) requests.fit = true;
  shown_time_ = session.time();
  ImGui::Text("t = %.3f s", shown_time_);
}

void Panel::stepping_section(Session& session, const FrameInfo& frame) {
  if (!ImGui::CollapsingHeader("Time stepping", ImGuiTreeNodeFlags_DefaultOpen)) return;
  SceneParameters& p = session.parameters();
  if (ImGui::BeginCombo("integrator", p.integrator.c_str())) {
    for (const std::string& name : integrator_names())
      if (ImGui::Selectable(name.c_str(), name == p.integrator)) {
        p.integrator = name;
        session.apply();
      }
    ImGui::EndCombo();
  }
  if (parameters_.draw_field(p, session.loaded_parameters(), "step")) session.apply();
  if (const std::optional<double> limit = session.critical_step()) {
    if (*limit == 0.0)
      ImGui::TextColored(warning_colour, "critical step: none, unstable at every h");
    else if (std::isinf(*limit))
      ImGui::Text("critical step: none, stable at every h");
    else if (session.critical_step_is_estimate() && p.step > *limit)
      ImGui::TextColored(warning_colour, "h > %.4g s, the step known to be safe: it may blow up",
                         *limit);
    else if (p.step > *limit)
      ImGui::TextColored(warning_colour, "h > critical step %.4g s: expect it to blow up", *limit);
    else if (session.critical_step_is_estimate())
      ImGui::Text("safe step %.4g s (h is %.0f%% of it)", *limit, 100 * p.step / *limit);
    else
      ImGui::Text("critical step %.4g s (h is %.0f%% of it)", *limit, 100 * p.step / *limit);
    if (session.critical_step_is_estimate()) {
      ImGui::PushStyleColor(ImGuiCol_Text, quiet_colour);
      ImGui::TextWrapped(
          "from a bound on omega_max (no eigen-solve above 100 particles): the critical step "
          "itself is larger (handout section 5)");
      ImGui::PopStyleColor();
    }
  } else {
    ImGui::PushStyleColor(ImGuiCol_Text, quiet_colour);
    ImGui::TextWrapped("critical step %s", session.critical_step_note().c_str());
    ImGui::PopStyleColor();
  }

  Pacing& pacing = session.pacing();
  ImGui::Checkbox("real time", &pacing.real_time);
  if (pacing.real_time) {
    ImGui::SliderScalar("real-time factor", ImGuiDataType_Double, &pacing.real_time_factor,
                        &min_factor, &max_factor, "%.3g", ImGuiSliderFlags_Logarithmic);
    ImGui::Text("%.3g steps of h per frame at 60 frames/s",
                pacing.real_time_factor * pacing.frame_interval / p.step);
  } else {
    ImGui::SliderInt("steps per frame", &pacing.steps_per_frame, 1, 1000, "%d",
                     ImGuiSliderFlags_Logarithmic);
  }
  const double fps = frame.frame_seconds > 0 ? 1.0 / frame.frame_seconds : 0.0;
  ImGui::Text("%.0f frames/s, %.1f ms a frame (%.1f ms stepping)", fps, 1e3 * frame.frame_seconds,
              1e3 * frame.stepping_seconds);
  ImGui::Text("last frame: %ld steps = %.1f ms simulated", frame.steps,
              1e3 * double(frame.steps) * p.step);
  if (frame.dropped_steps > 0)
    ImGui::TextColored(warning_colour,
                       "slower than real time: %ld steps dropped (stepping cannot keep up)",
                       frame.dropped_steps);
}

void Panel::display_section(Session& session, ViewSettings& settings) {
  // Looked for once a build: a 200×200 fabric has 238,000 springs to look through.
  if (families_of_build_ != session.builds()) {
    families_of_build_ = session.builds();
    present_families_ = {};
    if (const Simulation* sim = session.primary())
      for (const Spring& s : sim->scene().springs)
        present_families_[std::size_t(s.family)] = true;
  }
  for (int family = 0; family < int(present_families_.size()); ++family) {
    if (!present_families_[std::size_t(family)]) continue;
    bool shown = !settings.draw.hidden_families.count(family);
    const std::string label = std::string(to_string(SpringFamily(family))) + " springs";
    if (ImGui::Checkbox(label.c_str(), &shown)) {
      if (shown)
        settings.draw.hidden_families.erase(family);
      else
        settings.draw.hidden_families.insert(family);
    }
    ImGui::SameLine();
  }
  ImGui::NewLine();
  ImGui::Checkbox("force arrows", &settings.force_arrows);
  ImGui::SameLine();
  ImGui::TextColored(quiet_colour, "on the particle under the mouse");
  ImGui::SliderScalar("strain at full colour", ImGuiDataType_Double, &settings.draw.strain_scale,
                      &min_strain, &max_strain, "%.2g", ImGuiSliderFlags_Logarithmic);
  ImGui::TextColored(ImVec4(0.24f, 0.47f, 1.0f, 1.0f), "compressed");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.6f, 0.6f, 0.63f, 1.0f), "at rest");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(1.0f, 0.27f, 0.2f, 1.0f), "stretched");
  ImGui::SameLine();
  ImGui::TextColored(quiet_colour, "· squares are pinned");
}

void Panel::particle_section(Session& session, ViewSettings& settings, const FrameInfo& frame) {
  ImGui::TextColored(quiet_colour, "drag: move it · right-click: pin/unpin · shift+click: push");
  ImGui::TextColored(quiet_colour, "wheel: zoom · drag the background: pan · space: run/pause");
  const Simulation* sim = session.primary();
  if (frame.hovered >= 0) settings.selected = frame.hovered;
  if (!sim || settings.selected < 0 || settings.selected >= sim->particles().size()) {
    ImGui::Text("(no particle under the mouse)");
    return;
  }
  const int i = settings.selected;
  const Particles& p = sim->particles();
  const Vec2 force = spring_force_on(*sim, i);
  ImGui::Text("particle %d%s: r = (%.3f, %.3f) m", i, session.pinned(i) ? " (pinned)" : "",
              p.position(0, i), p.position(1, i));
  ImGui::Text("v = (%.3f, %.3f) m/s, springs' force (%.3f, %.3f) N", p.velocity(0, i),
              p.velocity(1, i), force.x(), force.y());
  if (ImGui::Button(session.pinned(i) ? "Unpin" : "Pin")) session.toggle_pin(i);
  ImGui::SameLine();
  if (ImGui::Button("Push")) session.push(i, settings.push_velocity);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::InputScalarN("##push", ImGuiDataType_Double, settings.push_velocity.data(), 2, nullptr,
                      nullptr, "%.2g m/s");
}

void Panel::plots(const Session& session, const Viewport& scene_area) {
  ImGui::SetNextWindowPos(ImVec2(scene_area.left, scene_area.top + scene_area.height));
  ImGui::SetNextWindowSize(ImVec2(scene_area.width, plot_height));
  ImGui::Begin(
      "##plots", nullptr,
      ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBackground);
  remember_background();
  const History& h = session.history();
  shown_plot_time_ = h.size() > 0 ? double(h.time.back()) : 0.0;
  ImGui::Columns(2, nullptr, false);
  ImGui::Text("energy over the last %.1f s",
              h.size() > 1 ? double(h.time.back() - h.time.front()) : 0.0);
  plot_frames_.clear();
  plot_frames_.push_back(plot("energy", "J",
                              {{"kinetic", &h.kinetic, IM_COL32(255, 196, 0, 255)},
                               {"potential", &h.potential, IM_COL32(90, 200, 255, 255)},
                               {"total", &h.total, IM_COL32(240, 240, 240, 255)}},
                              plot_height - 60.0f));
  ImGui::NextColumn();
  ImGui::Text("linear momentum");
  plot_frames_.push_back(plot("momentum", "kg·m/s",
                              {{"px", &h.momentum_x, IM_COL32(255, 110, 90, 255)},
                               {"py", &h.momentum_y, IM_COL32(120, 255, 120, 255)}},
                              plot_height - 60.0f));
  ImGui::Columns(1);
  ImGui::End();
}

namespace {
// A window over the top middle of the scene, at most 640 pixels wide, in its own colour (the
// caller ends it and pops the colour): the banner and the difference note.
void begin_overlay(const char* id, const Viewport& scene_area, const ImVec4& colour,
                   ImGuiWindowFlags extra) {
  const float width = std::min(scene_area.width - 40.0f, 640.0f);
  ImGui::SetNextWindowPos(ImVec2(scene_area.left + (scene_area.width - width) / 2, 20));
  ImGui::SetNextWindowSize(ImVec2(width, 0));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, colour);
  ImGui::Begin(id, nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize | extra);
}
}  // namespace

// A run that differs from the reference beside it, though nothing diverged: an amber note over
// the scene with the comparison's remark, so a large difference is seen, not only read.
void Panel::difference_note(const Session& session, const Viewport& scene_area) {
  const std::optional<Comparison> c = session.comparison();
  if (!c || c->remark.empty()) return;
  begin_overlay("##difference", scene_area, ImVec4(0.45f, 0.3f, 0.02f, 0.9f),
                ImGuiWindowFlags_NoInputs);
  ImGui::TextWrapped("Your run, %s", c->remark.c_str());
  ImGui::End();
  ImGui::PopStyleColor();
}

void Panel::banner(Session& session, const Viewport& scene_area) {
  const Problem& problem = session.problem();
  banner_shown_ = problem.kind != Problem::Kind::none;
  if (!banner_shown_) {
    difference_note(session, scene_area);
    return;
  }
  begin_overlay("##banner", scene_area, ImVec4(0.55f, 0.08f, 0.08f, 0.95f), 0);
  ImGui::SetWindowFontScale(1.25f);
  ImGui::TextWrapped("%s", problem.headline.c_str());
  ImGui::SetWindowFontScale(1.0f);
  if (problem.kind == Problem::Kind::diverged) {
    ImGui::Text("when: t = %.4g s", problem.time);
    if (problem.particle >= 0)
      ImGui::Text("where: particle %d (%s)", problem.particle, problem.quantity.c_str());
    else
      ImGui::Text("where: the whole scene (%s)", problem.quantity.c_str());
  }
  // The diagnosis's words are the one verdict on h and the code: nothing is added to them.
  ImGui::TextWrapped("%s", problem.detail.c_str());
  if (ImGui::Button("Reset")) session.reset();
  remember("banner reset");
  if (problem.kind == Problem::Kind::not_implemented) {
    ImGui::SameLine();
    if (ImGui::Button("Run the reference instead")) session.set_code(Code::reference);
  } else if (problem.kind == Problem::Kind::invalid) {
    ImGui::SameLine();
    if (ImGui::Button("Back to the scene's values")) session.load(session.source());
  }
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  rects_["banner"] = {at.x, at.y, at.x + size.x, at.y + size.y};
  ImGui::End();
  ImGui::PopStyleColor();
}

}  // namespace springlab::view
