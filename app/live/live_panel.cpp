#include "app/live/live_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "app/live/course.h"
#include "app/live/key_bindings.h"
#include "app/live/log_slider.h"
#include "app/live/param_limits.h"
#include "app/render/frame_text.h"

namespace invfree::live {

namespace {

const ImVec4 kNoteColor(1.0f, 0.82f, 0.35f, 1.0f);
const ImVec4 kDimColor(0.65f, 0.65f, 0.65f, 1.0f);

void remember(PanelState& ps, const char* name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  ps.rects[name] = {a.x, a.y, b.x, b.y};
}

// ImGui formats slider labels with printf: a literal '%' must be doubled.
std::string printf_safe(const std::string& s) {
  std::string out;
  for (char c : s) {
    out += c;
    if (c == '%') out += '%';
  }
  return out;
}

// A log slider over a material parameter: drags a position in [0, 1] (LogSlider) and
// shows the value itself. Returns true with *value set while it is being moved.
bool log_slider(PanelState& ps, const char* id, const char* label, const LogSlider& map,
                double current, double* value) {
  float t = static_cast<float>(map.position(current));
  const std::string text =
      printf_safe(std::string(label) + " = " + render::format_si(current, "Pa"));
  const bool changed =
      ImGui::SliderFloat(id, &t, 0.0f, 1.0f, text.c_str(), ImGuiSliderFlags_NoInput);
  remember(ps, id + 2);  // skip the "##"
  if (changed) *value = map.value(t);
  return changed;
}

// A double slider (ImGui's own, linear or logarithmic) whose Ctrl+click typed value may
// leave the range: it is then clamped with a note instead of applied.
bool clamped_slider(LiveController& lc, PanelState& ps, const char* label, const char* name,
                    double* v, Range range, const char* unit, const char* format,
                    bool logarithmic) {
  double edit = *v;
  const ImGuiSliderFlags flags =
      logarithmic ? ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat : 0;
  if (!ImGui::SliderScalar(label, ImGuiDataType_Double, &edit, &range.lo, &range.hi, format, flags))
    return false;
  remember(ps, name);
  const Clamped c = clamp_to_range(edit, *v, range, name, unit);
  if (!c.note.empty()) lc.note = c.note;
  if (c.value == *v) return false;
  *v = c.value;
  return true;
}

void apply(LiveController& lc, const SceneDef& next) {
  lc.apply(next);  // refusals leave their reason in lc.note
}

void playback_section(LiveController& lc, PanelState& ps, PanelRequests& req) {
  auto tip = [](const char* text) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
  };
  if (ImGui::Button(lc.playing() ? "Pause" : "Play", ImVec2(62, 0))) lc.set_playing(!lc.playing());
  remember(ps, "play");
  tip("Space");
  ImGui::SameLine();
  if (ImGui::Button("Step")) {
    lc.set_playing(false);
    lc.step_once();
  }
  remember(ps, "step");
  tip("S: one time step (pauses)");
  ImGui::SameLine();
  if (ImGui::Button("Reset")) lc.reset();
  remember(ps, "reset");
  tip("R: back to the initial state, keeping the settings");
  ImGui::SameLine();
  if (ImGui::Button("Screenshot")) req.screenshot = true;
  tip("Ctrl+P: numbered PNG of the window");
  ImGui::SameLine();
  if (ImGui::Button(ps.recording ? "Stop rec" : "Record")) req.toggle_record = true;
  remember(ps, "record");
  tip("Ctrl+R: PNG sequence DIR/frame_000000.png, ... (as invfree render)");
  if (!ps.last_output.empty()) ImGui::TextColored(kDimColor, "%s", ps.last_output.c_str());
}

void scene_section(LiveController& lc, PanelState& ps) {
  const auto& scenes = lc.scenes();
  int sel = lc.selected_scene();
  if (ImGui::BeginCombo("scene", scenes[sel].label.c_str())) {
    for (int i = 0; i < static_cast<int>(scenes.size()); ++i) {
      if (ImGui::Selectable(scenes[i].label.c_str(), i == sel)) lc.select_scene(i);
    }
    ImGui::EndCombo();
  }
  remember(ps, "scene");
  ImGui::SameLine();
  if (ImGui::SmallButton("restore")) lc.restore_scene_defaults();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the scene's own settings, from its initial state");
  if (const CourseChapter* c = course_chapter(scenes[sel].label); c && c->idea)
    ImGui::TextWrapped("Chapter %d: %s", c->chapter, c->idea);

  SceneDef next = lc.settings();
  const Model models[] = {Model::NeoHookean, Model::StableNeoHookean, Model::Arap, Model::Linear};
  if (ImGui::BeginCombo("model", render::model_display_name(next.model))) {
    for (Model m : models) {
      std::string label = render::model_display_name(m);
      if (model_allows_inversion(m)) label += "  (allows det F <= 0)";
      if (ImGui::Selectable(label.c_str(), m == next.model) && m != next.model) {
        next.model = m;
        apply(lc, next);
      }
    }
    ImGui::EndCombo();
  }
  remember(ps, "model");
}

void material_section(LiveController& lc, PanelState& ps) {
  SceneDef next = lc.settings();
  const LogSlider mu_map{kMuRange.lo, kMuRange.hi};
  const LogSlider lambda_map{kLambdaLogMin, kLambdaRange.hi, true};
  double v = 0.0;
  if (log_slider(ps, "##mu", "\xce\xbc", mu_map, next.lame.mu, &v)) {  // mu
    const MaterialEdit e = edit_mu(next.lame, v);
    next.lame = e.lame;
    if (!e.note.empty()) lc.note = e.note;
    apply(lc, next);
  }
  if (log_slider(ps, "##lambda", "\xce\xbb", lambda_map, next.lame.lambda, &v)) {  // lambda
    const MaterialEdit e = edit_lambda(next.lame, v);
    next.lame = e.lame;
    if (!e.note.empty()) lc.note = e.note;
    apply(lc, next);
  }
  // E and nu: shown beside the sliders, editable (applied on Enter or leaving the field).
  double E, nu;
  young_poisson_from_lame(next.lame, &E, &nu);
  ImGui::SetNextItemWidth(110);
  double e_in = E;
  const bool e_enter =
      ImGui::InputDouble("E (Pa)", &e_in, 0.0, 0.0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue);
  remember(ps, "E");
  if ((e_enter || ImGui::IsItemDeactivatedAfterEdit()) && e_in != E) {
    const MaterialEdit e = edit_young(next.lame, e_in);
    lc.note = e.note;
    next.lame = e.lame;
    apply(lc, next);
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  double nu_in = nu;
  const bool nu_enter = ImGui::InputDouble("\xce\xbd", &nu_in, 0.0, 0.0, "%.4f",
                                           ImGuiInputTextFlags_EnterReturnsTrue);
  remember(ps, "nu");
  if ((nu_enter || ImGui::IsItemDeactivatedAfterEdit()) && nu_in != nu) {
    const MaterialEdit e = edit_poisson(next.lame, nu_in);
    lc.note = e.note;
    next.lame = e.lame;
    apply(lc, next);
  }
}

void solver_section(LiveController& lc, PanelState& ps) {
  SceneDef next = lc.settings();
  if (clamped_slider(lc, ps, "h (s)", "h", &next.h, kTimeStepRange, "s", "%.4g", true))
    apply(lc, next);
  if (clamped_slider(lc, ps, "Newton tol (m/s)", "tol", &next.tol, kTolRange, "m/s", "%.2g", true))
    apply(lc, next);
  ImGui::SliderInt("steps / frame", &lc.steps_per_frame, 1, 10, "%d", ImGuiSliderFlags_AlwaysClamp);

  // n_seg rebuilds the mesh: applied when the slider is released, not at every pixel.
  int n = ps.n_seg_edit > 0 ? ps.n_seg_edit : next.n_seg;
  const int slider_max = std::max(ps.max_segments, kMinSegments + 1);
  ImGui::SliderInt("n_seg (mesh)", &n, kMinSegments, slider_max, "%d");
  remember(ps, "n_seg");
  if (ImGui::IsItemActive()) ps.n_seg_edit = n;
  if (ImGui::IsItemDeactivated()) {
    ps.n_seg_edit = -1;
    if (n != next.n_seg) {
      const Clamped c =
          clamp_to_range(n, next.n_seg, {double(kMinSegments), double(slider_max)}, "n_seg", "");
      next.n_seg = static_cast<int>(c.value);
      apply(lc, next);
      if (!c.note.empty())
        lc.note = c.note + " (the largest mesh measured to run at 30 frames/s here)";
    }
  } else if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("rebuilds the mesh and restarts when released (max %d: still >= 30 frames/s)",
                      slider_max);
  }
}

void contact_section(LiveController& lc, PanelState& ps) {
  SceneDef next = lc.settings();
  ImGui::BeginDisabled(!next.has_ground);
  if (clamped_slider(lc, ps, "friction", "friction", &next.friction, kFrictionRange, "", "%.3f",
                     false))
    apply(lc, next);
  ImGui::EndDisabled();
  ImGui::BeginDisabled(!next.has_ceiling);
  double speed = -next.ceiling_velocity;
  if (clamped_slider(lc, ps, "ceiling speed (m/s)", "ceiling speed", &speed, kCeilingSpeedRange,
                     "m/s", "%.3f", false)) {
    next.ceiling_velocity = -speed;
    apply(lc, next);
  }
  const SceneDef& original = lc.scenes()[lc.selected_scene()].scene;
  const Range stop =
      ceiling_stop_range(next.ground_y, next.has_ground, original.ceiling_y, next.side);
  if (clamped_slider(lc, ps, "ceiling stop (m)", "ceiling stop", &next.ceiling_stop, stop, "m",
                     "%.3f", false))
    apply(lc, next);
  ImGui::EndDisabled();
  if (!next.has_ceiling) ImGui::TextColored(kDimColor, "(this scene has no ceiling)");
  clamped_slider(lc, ps, "grab spring (N/m)", "grab spring", &lc.pull_stiffness,
                 kPullStiffnessRange, "N/m", "%.3g", true);
}

void stats_section(const LiveController& lc, PanelState& ps) {
  const Simulation& sim = lc.simulation();
  const StateStats& st = lc.stats();
  // (frames/s is in the window title: a screenshot of the same state is then the same picture)
  ImGui::Text("step %ld    t = %.3f s", sim.step_count, sim.time);
  if (lc.has_stepped()) {
    const StepReport& r = lc.last_report();
    ImGui::Text("%.2f ms/step    Newton %d it    residual %.2e m/s", r.wall_ms, r.newton_iterations,
                r.residual);
  } else {
    ImGui::TextColored(kDimColor, "no step yet");
  }
  const ImVec4 inverted_color =
      st.inverted > 0 ? ImVec4(0.2f, 0.9f, 0.3f, 1.0f) : ImGui::GetStyleColorVec4(ImGuiCol_Text);
  ImGui::Text("det F in [%.4f, %.4f]", st.min_det_f, st.max_det_f);
  ImGui::SameLine();
  ImGui::TextColored(inverted_color, "  %d inverted", st.inverted);
  ImGui::Text("%d nodes, %d triangles", sim.mesh.node_count(), sim.mesh.triangle_count());

  const float plot_w = ImGui::GetContentRegionAvail().x;
  char overlay[96];
  const auto ms = lc.ms_history().values();
  if (!ms.empty()) {
    const float mean = std::accumulate(ms.begin(), ms.end(), 0.0f) / ms.size();
    std::snprintf(overlay, sizeof overlay, "ms/step: last %.2f, mean %.2f, max %.2f", ms.back(),
                  mean, lc.ms_history().max());
  } else {
    std::snprintf(overlay, sizeof overlay, "ms/step");
  }
  ImGui::PlotLines("##ms", ms.data(), static_cast<int>(ms.size()), 0, overlay, 0.0f, FLT_MAX,
                   ImVec2(plot_w, 48));
  remember(ps, "ms_plot");
  const auto det = lc.min_det_history().values();
  std::snprintf(overlay, sizeof overlay, "min det F over the last %zu steps", det.size());
  ImGui::PlotLines("##mindet", det.data(), static_cast<int>(det.size()), 0, overlay, FLT_MAX,
                   FLT_MAX, ImVec2(plot_w, 48));
  remember(ps, "min_det_plot");
}

}  // namespace

PanelRequests draw_panel(LiveController& lc, PanelState& ps) {
  PanelRequests req;
  ps.rects.clear();
  if (!ps.visible) return req;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(vp->WorkPos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(ps.width, vp->WorkSize.y), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(1.0f);  // opaque: the picture's plane lines must not show through
  ImGui::Begin("invfree live", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::PushItemWidth(ps.width * 0.55f);
  ImGui::TextColored(kDimColor, "F1: keys and mouse    Tab: hide this panel");
  playback_section(lc, ps, req);
  if (!lc.note.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kNoteColor);
    ImGui::TextWrapped("%s", lc.note.c_str());
    ImGui::PopStyleColor();
    remember(ps, "note");
  }
  ImGui::Separator();
  scene_section(lc, ps);
  ImGui::Separator();
  material_section(lc, ps);
  ImGui::Separator();
  solver_section(lc, ps);
  ImGui::Separator();
  contact_section(lc, ps);
  ImGui::Separator();
  stats_section(lc, ps);
  ImGui::PopItemWidth();
  ImGui::End();
  return req;
}

void draw_banners(const LiveController& lc, const PanelState& ps, const WidgetRect& area) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float cx = 0.5f * (area.x0 + area.x1);
  float y = area.y0 + 16.0f;
  ImFont* big = ps.big_font ? ps.big_font : ImGui::GetFont();
  const float big_size = big->FontSize;
  if (!lc.playing()) {
    const char* text = "PAUSED";
    const ImVec2 sz = big->CalcTextSizeA(big_size, FLT_MAX, 0.0f, text);
    const ImVec2 a(cx - 0.5f * sz.x - 18.0f, y), b(cx + 0.5f * sz.x + 18.0f, y + sz.y + 10.0f);
    dl->AddRectFilled(a, b, IM_COL32(30, 30, 30, 200), 8.0f);
    dl->AddText(big, big_size, ImVec2(a.x + 18.0f, a.y + 5.0f), IM_COL32(255, 255, 255, 255), text);
    y = b.y + 8.0f;
  }
  if (!lc.banner.empty()) {
    const float wrap = std::min(area.x1 - area.x0 - 40.0f, 720.0f);
    ImFont* f = ImGui::GetFont();
    const ImVec2 sz = f->CalcTextSizeA(ImGui::GetFontSize(), FLT_MAX, wrap, lc.banner.c_str());
    const ImVec2 a(cx - 0.5f * sz.x - 12.0f, y), b(cx + 0.5f * sz.x + 12.0f, y + sz.y + 12.0f);
    dl->AddRectFilled(a, b, IM_COL32(170, 20, 30, 230), 6.0f);
    dl->AddText(f, ImGui::GetFontSize(), ImVec2(a.x + 12.0f, a.y + 6.0f),
                IM_COL32(255, 255, 255, 255), lc.banner.c_str(), nullptr, wrap);
  }
  if (ps.recording) {
    const ImVec2 p(area.x1 - 90.0f, area.y0 + 24.0f);
    dl->AddCircleFilled(p, 9.0f, IM_COL32(220, 20, 20, 255));
    dl->AddText(ImVec2(p.x + 16.0f, p.y - 0.5f * ImGui::GetFontSize()), IM_COL32(220, 20, 20, 255),
                "REC");
  }
}

void draw_help_overlay(PanelState& ps) {
  if (!ps.show_help) return;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(
      ImVec2(vp->WorkPos.x + 0.5f * vp->WorkSize.x, vp->WorkPos.y + 0.5f * vp->WorkSize.y),
      ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(1.0f);
  ImGui::Begin("Keys and mouse (F1 closes)", &ps.show_help,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoCollapse);
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingFixedFit)) {
    for (const auto& b : key_bindings()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(kNoteColor, "%s", b.key_name);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(b.description);
    }
    for (const auto& m : mouse_bindings()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(kNoteColor, "%s", m.gesture);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(m.description);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace invfree::live
