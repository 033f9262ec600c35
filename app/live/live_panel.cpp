#include "app/live/live_panel.h"

#include <imgui.h>
#include <imgui_internal.h>  // TempInputIsActive: a slider being typed into

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include "app/body_extent.h"
#include "app/live/method_picker.h"
#include "app/live/scene_label.h"
#include "app/live/course.h"
#include "app/live/key_bindings.h"
#include "app/live/log_slider.h"
#include "app/live/panel_layout.h"
#include "app/live/step_time.h"
#include "app/live/param_limits.h"
#include "app/live/plot_range.h"
#include "app/live/scene_ideas.h"
#include "app/render/frame_text.h"

namespace invfree::live {

namespace {

const ImVec4 kNoteColor(1.0f, 0.82f, 0.35f, 1.0f);
const ImVec4 kDimColor(0.65f, 0.65f, 0.65f, 1.0f);

void remember(PanelState& ps, const char* name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  ps.rects[name] = {a.x, a.y, b.x, b.y};
}

// What a slider did this frame.
enum class SliderEdit { None, Dragged, Typed };

// Draws `text` inside the slider just drawn (the last item), in the half its handle (at t
// in [0, 1]) is not in, and the slider's label after it: the caller drew the slider with
// ImGui's text colour cleared, so the handle never hides the value.
void draw_slider_value(const char* label, float t, const std::string& text) {
  const ImGuiStyle& style = ImGui::GetStyle();
  const ImVec2 a = ImGui::GetItemRectMin();
  const float w = ImGui::CalcItemWidth();
  const ImVec2 b(a.x + w, ImGui::GetItemRectMax().y);
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  const float grab = std::max(style.GrabMinSize, 1.0f);
  const float travel = w - 2.0f * style.FramePadding.x - grab;
  const float grab_x0 = a.x + style.FramePadding.x + std::clamp(t, 0.0f, 1.0f) * travel;
  const float left_room = grab_x0 - a.x, right_room = b.x - (grab_x0 + grab);
  const float x =
      right_room >= left_room ? b.x - style.FramePadding.x - size.x : a.x + style.FramePadding.x;
  ImGui::GetWindowDrawList()->AddText(ImVec2(x, a.y + style.FramePadding.y),
                                      ImGui::GetColorU32(ImGuiCol_Text), text.c_str());
  const char* hidden = std::strstr(label, "##");
  const char* end = hidden ? hidden : label + std::strlen(label);
  if (end != label)
    ImGui::GetWindowDrawList()->AddText(
        ImVec2(b.x + style.ItemInnerSpacing.x, a.y + style.FramePadding.y),
        ImGui::GetColorU32(ImGuiCol_Text), label, end);
}

// A slider of a position t in [0, 1] (the caller maps it to the value) that keeps its
// value `text` readable: ImGui draws the frame and the handle only, and the text goes to
// the side of the frame with more room beside the handle. Ctrl+click opens a text field in
// its place (until Enter, or a click elsewhere, which applies it; Esc cancels): *typed is
// then the number typed. `label` is ImGui's (shown right of the slider unless "##...").
SliderEdit readable_slider(PanelState& ps, const char* label, const char* name, float* t,
                           const std::string& text, double current, double* typed) {
  const ImGuiIO& io = ImGui::GetIO();
  if (ps.typing == name) {
    if (ps.typing_frames++ == 0) ImGui::SetKeyboardFocusHere();
    const std::string field = std::string("##typed_") + name;
    const bool enter = ImGui::InputDouble(
        field.c_str(), &ps.typed, 0.0, 0.0, "%.6g",
        ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
    remember(ps, name);
    if (enter || ImGui::IsItemDeactivatedAfterEdit()) {
      ps.typing.clear();
      *typed = ps.typed;
      return SliderEdit::Typed;
    }
    if (ps.typing_frames > 2 && !ImGui::IsItemActive()) ps.typing.clear();  // Esc, elsewhere
    return SliderEdit::None;
  }
  // Ctrl+click on last frame's slider: type (the slider must not see the click and jump).
  if (auto it = ps.previous_rects.find(name); it != ps.previous_rects.end() && io.KeyCtrl &&
                                              ImGui::IsMouseClicked(0) &&
                                              ImGui::IsWindowHovered()) {
    const WidgetRect& r = it->second;
    if (io.MousePos.x >= r.x0 && io.MousePos.x < r.x1 && io.MousePos.y >= r.y0 &&
        io.MousePos.y < r.y1) {
      ps.typing = name;
      ps.typed = current;
      ps.typing_frames = 0;
      return readable_slider(ps, label, name, t, text, current, typed);
    }
  }
  ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(0, 0, 0, 0));  // only the label, below
  const bool changed = ImGui::SliderFloat(label, t, 0.0f, 1.0f, "", ImGuiSliderFlags_NoInput);
  ImGui::PopStyleColor();
  remember(ps, name);
  draw_slider_value(label, *t, text);
  return changed ? SliderEdit::Dragged : SliderEdit::None;
}

// An ImGui slider drawn by `widget` whose value `text` goes where its handle is not (at
// t in [0, 1]); Ctrl+click still types into it as ImGui does (ImGui's own text field is
// shown while typing).
template <class Widget>
bool slider_with_readable_value(const char* label, float t, const std::string& text,
                                Widget widget) {
  const bool typing = ImGui::TempInputIsActive(ImGui::GetID(label));
  if (!typing) ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(0, 0, 0, 0));
  const bool changed = widget();
  if (!typing) {
    ImGui::PopStyleColor();
    draw_slider_value(label, t, text);
  }
  return changed;
}

// A log slider over a material parameter (LogSlider): dragged or typed, *value is the
// value asked for.
constexpr const char* kMassSpringLabel = "mass-spring";

bool log_slider(PanelState& ps, const char* id, const char* label, const LogSlider& map,
                double current, double* value, const char* unit = "Pa") {
  float t = static_cast<float>(map.position(current));
  const std::string text = std::string(label) + " = " + render::format_si(current, unit);
  double typed = 0.0;
  switch (readable_slider(ps, id, id + 2, &t, text, current, &typed)) {
    case SliderEdit::Dragged:
      *value = map.value(t);
      return true;
    case SliderEdit::Typed:
      *value = typed;
      return true;
    case SliderEdit::None:
      break;
  }
  return false;
}

// A double slider, linear or logarithmic over `range`, whose typed value may leave the
// range: it is then clamped with a note. `shown_instead`: a text in place of the value.
bool clamped_slider(LiveController& lc, PanelState& ps, const char* label, const char* name,
                    double* v, Range range, const char* unit, const char* format, bool logarithmic,
                    const char* shown_instead = nullptr) {
  const auto position = [&](double x) {
    if (logarithmic) return LogSlider{range.lo, range.hi}.position(x);
    return range.hi > range.lo ? std::clamp((x - range.lo) / (range.hi - range.lo), 0.0, 1.0) : 0.0;
  };
  float t = static_cast<float>(position(*v));
  char text[64];
  std::snprintf(text, sizeof text, format, *v);
  if (shown_instead) std::snprintf(text, sizeof text, "%s", shown_instead);
  double edit = *v;
  switch (readable_slider(ps, label, name, &t, text, *v, &edit)) {
    case SliderEdit::Dragged:
      edit = logarithmic ? LogSlider{range.lo, range.hi}.value(t)
                         : (t >= 1.0f ? range.hi : range.lo + t * (range.hi - range.lo));
      break;
    case SliderEdit::Typed:
      break;
    case SliderEdit::None:
      return false;
  }
  const Clamped c = clamp_to_range(edit, *v, range, name, unit);
  if (!c.note.empty()) lc.note = c.note;
  if (c.value == *v) return false;
  *v = c.value;
  return true;
}

void apply(LiveController& lc, const SceneDef& next) {
  lc.apply(next);  // refusals leave their reason in lc.note
}

// The n_seg row's style by touch (panel_layout.h's kTouchTarget high, a wide handle), for
// the scope of one row; nothing without touch controls.
struct NsegTouchStyle {
  bool on;
  explicit NsegTouchStyle(const PanelState& ps) : on(ps.touch) {
    if (!on) return;
    const float pad = std::max(0.0f, 0.5f * (kTouchTarget * ps.ui_scale - ImGui::GetFontSize()));
    ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, ImVec2(ImGui::GetStyle().FramePadding.x, pad));
    ImGui::PushStyleVar(ImGuiStyleVar_GrabMinSize, 0.6f * kTouchTarget * ps.ui_scale);
  }
  ~NsegTouchStyle() {
    if (on) ImGui::PopStyleVar(2);
  }
  NsegTouchStyle(const NsegTouchStyle&) = delete;
  NsegTouchStyle& operator=(const NsegTouchStyle&) = delete;
};

// One mesh step down or up by a tap: a finger cannot hit one of 37 values on a 200-px slider.
void n_seg_buttons(LiveController& lc, PanelState& ps, bool enabled, int slider_max) {
  const float side = kTouchTarget * ps.ui_scale;
  SceneDef next = lc.settings();
  int step = 0;
  ImGui::BeginDisabled(!enabled);
  ImGui::SameLine();
  if (ImGui::Button("-##n_seg", ImVec2(side, side))) step = -1;
  remember(ps, "n_seg_minus");
  ImGui::SameLine();
  if (ImGui::Button("+##n_seg", ImVec2(side, side))) step = 1;
  remember(ps, "n_seg_plus");
  ImGui::EndDisabled();
  const int n = std::clamp(next.n_seg + step, kMinSegments, slider_max);
  if (step != 0 && n != next.n_seg) {
    next.n_seg = n;
    apply(lc, next);
  }
}

void playback_section(LiveController& lc, PanelState& ps, PanelRequests& req) {
  auto tip = [](const char* text) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
  };
  if (ImGui::Button(lc.playing() ? "Pause" : "Play", ImVec2(62 * ps.ui_scale, 0)))
    lc.set_playing(!lc.playing());
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
}

void scene_section(LiveController& lc, PanelState& ps) {
  const auto& scenes = lc.scenes();
  int sel = lc.selected_scene();
  // The whole row but the restore button, and the list as wide as its longest name: no
  // name is clipped; a scene file shows as its file name (its path in the tooltip).
  float widest = 0.0f;
  for (const SceneChoice& c : scenes)
    widest = std::max(widest, ImGui::CalcTextSize(scene_display_name(c.label).c_str()).x);
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x -
                          ImGui::CalcTextSize("restore").x - 3.0f * ImGui::GetStyle().ItemSpacing.x);
  ImGui::SetNextWindowSizeConstraints(
      ImVec2(widest + 3.0f * ImGui::GetStyle().WindowPadding.x, 0.0f), ImVec2(FLT_MAX, FLT_MAX));
  if (ImGui::BeginCombo("##scene", scene_display_name(scenes[sel].label).c_str())) {
    for (int i = 0; i < static_cast<int>(scenes.size()); ++i) {
      if (ImGui::Selectable(scene_display_name(scenes[i].label).c_str(), i == sel))
        lc.select_scene(i);
      if (scene_display_name(scenes[i].label) != scenes[i].label && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", scenes[i].label.c_str());
    }
    ImGui::EndCombo();
  }
  remember(ps, "scene");
  if (scene_display_name(scenes[sel].label) != scenes[sel].label && ImGui::IsItemHovered())
    ImGui::SetTooltip("%s", scenes[sel].label.c_str());
  ImGui::SameLine();
  if (ImGui::SmallButton("restore")) lc.restore_scene_defaults();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the scene's own settings, from its initial state");
  if (const CourseChapter* c = course_chapter(scenes[sel].label); c && c->idea)
    ImGui::TextWrapped("Chapter %d: %s", c->chapter, c->idea);
  else if (const char* idea = scene_idea(scenes[sel].label))
    ImGui::TextWrapped("%s", idea);

  SceneDef next = lc.settings();
  const Model models[] = {Model::NeoHookean, Model::StableNeoHookean, Model::Arap, Model::Linear};
  // The course's chapters 1-5 model springs, not triangles: the picker says so and can
  // switch either way (the mesh is rebuilt).
  const char* shown =
      next.has_mass_spring ? kMassSpringLabel : render::model_display_name(next.model);
  // The model and the method (method_picker.h) share a row.
  const float half = 0.5f * (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x);
  ImGui::SetNextItemWidth(half);
  if (ImGui::BeginCombo("##model", shown)) {
    for (Model m : models) {
      std::string label = render::model_display_name(m);
      if (model_allows_inversion(m)) label += "  (allows det F <= 0)";
      const bool current = !next.has_mass_spring && m == next.model;
      if (ImGui::Selectable(label.c_str(), current) && !current) {
        next.model = m;
        next.has_mass_spring = false;
        apply(lc, next);
      }
    }
    if (ImGui::Selectable(kMassSpringLabel, next.has_mass_spring) && !next.has_mass_spring) {
      next.has_mass_spring = true;
      apply(lc, next);
    }
    ImGui::EndCombo();
  }
  remember(ps, "model");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the material model");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(half);
  method_row(lc, ps);
}

void material_section(LiveController& lc, PanelState& ps) {
  SceneDef next = lc.settings();
  if (next.has_mass_spring) {  // the springs' k instead of the triangles' material
    const LogSlider k_map{kSpringStiffnessRange.lo, kSpringStiffnessRange.hi};
    double k = 0.0;
    if (log_slider(ps, "##k", "k", k_map, next.spring_stiffness, &k, "N/m")) {
      next.spring_stiffness = std::clamp(k, kSpringStiffnessRange.lo, kSpringStiffnessRange.hi);
      if (next.spring_stiffness != k) lc.note = "k clamped to the slider's range";
      apply(lc, next);
    }
    return;
  }
  body_materials_rows(lc, ps);
  const LogSlider mu_map{kMuRange.lo, kMuRange.hi};
  const LogSlider lambda_map{kLambdaLogMin, kLambdaRange.hi, true};
  double v = 0.0;
  if (log_slider(ps, "##mu", "\xce\xbc", mu_map, next.lame.mu, &v)) {  // mu
    const MaterialEdit e = edit_mu(next.lame, v);
    set_material_of_every_body(next, e.lame);
    if (!e.note.empty()) lc.note = e.note;
    apply(lc, next);
  }
  if (log_slider(ps, "##lambda", "\xce\xbb", lambda_map, next.lame.lambda, &v)) {  // lambda
    const MaterialEdit e = edit_lambda(next.lame, v);
    set_material_of_every_body(next, e.lame);
    if (!e.note.empty()) lc.note = e.note;
    apply(lc, next);
  }
  // E and nu: shown beside the sliders, editable (applied on Enter or leaving the field).
  double E, nu;
  young_poisson_from_lame(next.lame, &E, &nu);
  ImGui::SetNextItemWidth(110 * ps.ui_scale);
  double e_in = E;
  const bool e_enter =
      ImGui::InputDouble("E (Pa)", &e_in, 0.0, 0.0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue);
  remember(ps, "E");
  if ((e_enter || ImGui::IsItemDeactivatedAfterEdit()) && e_in != E) {
    const MaterialEdit e = edit_young(next.lame, e_in);
    lc.note = e.note;
    set_material_of_every_body(next, e.lame);
    apply(lc, next);
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70 * ps.ui_scale);
  double nu_in = nu;
  const bool nu_enter = ImGui::InputDouble("\xce\xbd", &nu_in, 0.0, 0.0, "%.4f",
                                           ImGuiInputTextFlags_EnterReturnsTrue);
  remember(ps, "nu");
  if ((nu_enter || ImGui::IsItemDeactivatedAfterEdit()) && nu_in != nu) {
    const MaterialEdit e = edit_poisson(next.lame, nu_in);
    lc.note = e.note;
    set_material_of_every_body(next, e.lame);
    apply(lc, next);
  }
}

// What n_seg means for a scene's bodies: `any` when it sets some body's mesh (a square's
// grid, or a meshed shape's default max_edge); `shape_edge`: the first such meshed shape's
// max_edge at this n_seg (0 when no meshed shape reads n_seg).
struct MeshedByNseg {
  bool any = false;
  double shape_edge = 0.0;
};
MeshedByNseg meshed_by_n_seg(const SceneDef& s) {
  MeshedByNseg m;
  for (int k = 0; k < body_count(s); ++k) {
    const PlacedBody b = placed_body(s, k);
    if (b.shape.kind == ShapeKind::Square) {
      m.any = true;
    } else if (b.shape.kind != ShapeKind::MeshFile && !(b.shape.max_edge > 0.0)) {
      m.any = true;
      if (m.shape_edge == 0.0) m.shape_edge = shape_max_edge(b.shape, b.n_seg);
    }
  }
  return m;
}

void solver_section(LiveController& lc, PanelState& ps) {
  SceneDef next = lc.settings();
  if (clamped_slider(lc, ps, "h (s)", "h", &next.h, kTimeStepRange, "s", "%.4g", true))
    apply(lc, next);
  if (clamped_slider(lc, ps, "Newton tol (m/s)", "tol", &next.tol, kTolRange, "m/s", "%.2g", true))
    apply(lc, next);
  slider_with_readable_value("steps / frame", (lc.steps_per_frame - 1) / 9.0f,
                             std::to_string(lc.steps_per_frame), [&] {
                               return ImGui::SliderInt("steps / frame", &lc.steps_per_frame, 1, 10,
                                                       "%d", ImGuiSliderFlags_AlwaysClamp);
                             });

  // n_seg rebuilds the mesh: applied when the slider is released, not at every pixel. A
  // meshed shape reads it as its default max_edge (the longer side / n_seg); a shape whose
  // scene gives max_edge, or a mesh file, ignores it: the slider is then disabled.
  const MeshedByNseg meshing = meshed_by_n_seg(next);
  int n = ps.n_seg_edit > 0 ? ps.n_seg_edit : next.n_seg;
  const int slider_max = std::max(ps.max_segments, kMinSegments + 1);
  ImGui::BeginDisabled(!meshing.any);
  // By touch: a finger-high row, the label inside (the -/+ buttons take its place).
  const NsegTouchStyle touch(ps);
  const char* n_seg_label = ps.touch ? "##n_seg (mesh)" : "n_seg (mesh)";
  slider_with_readable_value(
      n_seg_label, float(n - kMinSegments) / float(slider_max - kMinSegments),
      ps.touch ? "n_seg = " + std::to_string(n) : std::to_string(n),
      [&] { return ImGui::SliderInt(n_seg_label, &n, kMinSegments, slider_max, "%d"); });
  ImGui::EndDisabled();
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
  } else if (!meshing.any && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip(
        "this scene's shape sets its own mesh (max_edge or a mesh file):\n"
        "n_seg does not change it");
  } else if (meshing.shape_edge > 0.0 && ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "a meshed shape: max_edge = its longer side / n_seg = %.3g m;\n"
        "rebuilds the mesh and restarts when released (max %d)",
        meshing.shape_edge, slider_max);
  } else if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("rebuilds the mesh and restarts when released (max %d: still >= 30 frames/s)",
                      slider_max);
  }
  if (ps.touch) n_seg_buttons(lc, ps, meshing.any, slider_max);
}

void contact_section(LiveController& lc, PanelState& ps) {
  SceneDef next = lc.settings();
  ImGui::BeginDisabled(!next.has_ground);
  if (clamped_slider(lc, ps, "friction", "friction", &next.friction, kFrictionRange, "", "%.3f",
                     false))
    apply(lc, next);
  ImGui::EndDisabled();
  // Switches the boundary's contact with itself (docs/method.md#self-contact), on by
  // default: unticked, a fine mesh's folds pass through themselves and the class sees what
  // the term prevents. Greyed out and unticked where it cannot run (springs, fixed nodes:
  // self_contact_can_run).
  const bool can_run = self_contact_can_run(next);
  bool self_contact = next.self_contact_on();
  ImGui::BeginDisabled(!can_run);
  if (ImGui::Checkbox("self-contact (boundary against itself)", &self_contact) && can_run) {
    next.has_self_contact = self_contact;
    apply(lc, next);
  }
  ImGui::EndDisabled();
  // Without a ceiling its two sliders are greyed out and say so in place of their values
  // (a line of its own would push the panel's last row out of a 1280x720 window).
  ImGui::BeginDisabled(!next.has_ceiling);
  const char* no_ceiling = next.has_ceiling ? nullptr : "no ceiling";
  double speed = -next.ceiling_velocity;
  if (clamped_slider(lc, ps, "ceiling speed (m/s)", "ceiling speed", &speed, kCeilingSpeedRange,
                     "m/s", "%.3f", false, no_ceiling)) {
    next.ceiling_velocity = -speed;
    apply(lc, next);
  }
  const SceneDef& original = lc.scenes()[lc.selected_scene()].scene;
  const Range stop = ceiling_stop_range(next.ground_y, next.has_ground, original.ceiling_y,
                                        scene_length_scale(next));
  if (clamped_slider(lc, ps, "ceiling stop (m)", "ceiling stop", &next.ceiling_stop, stop, "m",
                     "%.3f", false, no_ceiling))
    apply(lc, next);
  ImGui::EndDisabled();
  clamped_slider(lc, ps, "grab spring (N/m)", "grab spring", &lc.pull_stiffness,
                 kPullStiffnessRange, "N/m", "%.3g", true);
}

// A plot's height: three text lines where the window has the room, down to two (its top
// and bottom values beside it) so that the panel's last row ends inside the window (at
// 1280x720, UI scale 1, 50 px); less than that scrolls.
float plot_height() {
  const float line = ImGui::GetTextLineHeightWithSpacing();
  return std::clamp(ImGui::GetContentRegionAvail().y, 2.0f * line, 3.0f * line);
}

// The top and bottom values of a plot `h` high, beside it (right of the last item).
void y_range_labels(const char* top, const char* bottom, float width, float h) {
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::TextUnformatted(top);
  ImGui::Dummy(ImVec2(width, h - 2.0f * ImGui::GetTextLineHeightWithSpacing()));
  ImGui::TextUnformatted(bottom);
  ImGui::EndGroup();
}

// A plot with its title above and its y range written beside it (the top and bottom
// values), so that a change of 0.001 is not read as a steep ramp; the range spans at least
// `min_span` around the data.
void labelled_plot(PanelState& ps, const char* name, const char* title,
                   const std::vector<float>& values, float min_span, const char* format) {
  ImGui::TextUnformatted(title);
  const auto [lo, hi] = plot_y_range(values, min_span);
  char top[32], bottom[32];
  std::snprintf(top, sizeof top, format, hi);
  std::snprintf(bottom, sizeof bottom, format, lo);
  const ImGuiStyle& style = ImGui::GetStyle();
  const float label_w = std::max(ImGui::CalcTextSize(top).x, ImGui::CalcTextSize(bottom).x);
  const float h = plot_height();
  const float w = ImGui::GetContentRegionAvail().x - label_w - style.ItemSpacing.x;
  const std::string id = std::string("##") + name;
  ImGui::PlotLines(id.c_str(), values.data(), static_cast<int>(values.size()), 0, nullptr, lo, hi,
                   ImVec2(w, h));
  remember(ps, name);
  y_range_labels(top, bottom, label_w, h);
}

// Kinetic, elastic, gravitational and contact energy over the last steps on one y axis
// (its range written beside it), with a coloured legend.
void energy_plot(const LiveController& lc, PanelState& ps) {
  // The four, then their total (white): what implicit Euler's damping takes out of it
  // shows as the total falling.
  static const ImU32 colors[5] = {IM_COL32(240, 170, 40, 255), IM_COL32(90, 170, 255, 255),
                                  IM_COL32(150, 220, 120, 255), IM_COL32(240, 90, 90, 255),
                                  IM_COL32(245, 245, 245, 255)};
  const auto& history = lc.energy_history();
  std::vector<float> series[5];
  float lo = 0.0f, hi = 0.0f;
  bool any = false;
  for (int k = 0; k < 4; ++k) series[k] = history[k].values();
  series[4] = series[0];
  for (int k = 1; k < 4; ++k)
    for (std::size_t i = 0; i < series[4].size() && i < series[k].size(); ++i)
      series[4][i] += series[k][i];
  for (int k = 0; k < 5; ++k) {
    for (float v : series[k]) {
      lo = any ? std::min(lo, v) : v;
      hi = any ? std::max(hi, v) : v;
      any = true;
    }
  }
  if (hi - lo < 1e-3f) {
    lo -= 5e-4f;
    hi += 5e-4f;
  }
  static const char* const kTotal = "total";
  for (int k = 0; k < 5; ++k) {
    // The legend wraps where the panel's width ends (a scale of 3 fits two names a row).
    const char* name = k < 4 ? LiveController::kEnergyNames[k] : kTotal;
    if (k > 0 && ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x +
                         ImGui::CalcTextSize(name).x <
                     ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x)
      ImGui::SameLine();
    ImGui::PushStyleColor(ImGuiCol_Text, colors[k]);
    ImGui::TextUnformatted(name);
    ImGui::PopStyleColor();
  }
  char top[32], bottom[32];
  std::snprintf(top, sizeof top, "%.3g J", hi);
  std::snprintf(bottom, sizeof bottom, "%.3g J", lo);
  const ImGuiStyle& style = ImGui::GetStyle();
  const float label_w = std::max(ImGui::CalcTextSize(top).x, ImGui::CalcTextSize(bottom).x);
  const float h = plot_height();
  const float w = ImGui::GetContentRegionAvail().x - label_w - style.ItemSpacing.x;
  const ImVec2 a = ImGui::GetCursorScreenPos(), b(a.x + w, a.y + h);
  ImGui::Dummy(ImVec2(w, h));
  remember(ps, "energy_plot");
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(a, b, ImGui::GetColorU32(ImGuiCol_FrameBg), style.FrameRounding);
  for (int k = 0; k < 5; ++k) {
    const auto& v = series[k];
    if (v.size() < 2) continue;
    std::vector<ImVec2> points(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      points[i] = ImVec2(a.x + 2.0f + (w - 4.0f) * i / float(v.size() - 1),
                         b.y - 2.0f - (h - 4.0f) * (v[i] - lo) / (hi - lo));
    dl->AddPolyline(points.data(), static_cast<int>(points.size()), colors[k], 0,
                    std::max(1.5f, 1.5f * ps.ui_scale));
  }
  y_range_labels(top, bottom, label_w, h);
}

void stats_section(const LiveController& lc, PanelState& ps) {
  const Simulation& sim = lc.simulation();
  const StateStats& st = lc.stats();
  // (frames/s is in the window title: a screenshot of the same state is then the same picture)
  ImGui::Text("step %ld    t = %.3f s    %d nodes", sim.step_count, sim.time,
              sim.mesh.node_count());
  if (lc.has_stepped()) {
    const StepReport& r = lc.last_report();
    // (the wall-clock figure last: its changing digits move nothing else on the line)
    const double ms = shown_step_ms(lc.ms_history().values(), r.wall_ms);
    ImGui::Text("Newton %d it    residual %.2e m/s    %s", r.newton_iterations, r.residual,
                step_time_text(ms).c_str());
  } else {
    ImGui::TextColored(kDimColor, "no step yet");
  }
  // Particles only (the course's chapter 0): no triangles, so no det F to show.
  const bool triangles = sim.mesh.triangle_count() > 0;
  if (triangles) {
    const ImVec4 inverted_color =
        st.inverted > 0 ? ImVec4(0.2f, 0.9f, 0.3f, 1.0f) : ImGui::GetStyleColorVec4(ImGuiCol_Text);
    ImGui::Text("det F in [%.4f, %.4f]", st.min_det_f, st.max_det_f);
    ImGui::SameLine();
    ImGui::TextColored(inverted_color, "  %d inverted", st.inverted);
  } else {
    ImGui::TextColored(kDimColor, "no triangles: particles and springs, no det F");
  }

  if (ImGui::BeginTabBar("plots")) {
    if (ImGui::BeginTabItem("energy")) {
      energy_plot(lc, ps);
      ImGui::EndTabItem();
    }
    if (triangles && ImGui::BeginTabItem("min det F")) {
      const auto det = lc.min_det_history().values();
      char title[64];
      std::snprintf(title, sizeof title, "min det F, last %zu steps", det.size());
      labelled_plot(ps, "min_det_plot", title, det, 0.01f, "%.4f");
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("ms/step")) {
      const auto ms = lc.ms_history().values();
      char title[96] = "ms per step";
      if (!ms.empty()) {
        const float mean = std::accumulate(ms.begin(), ms.end(), 0.0f) / ms.size();
        std::snprintf(title, sizeof title, "last %s, mean %s", step_time_text(ms.back()).c_str(),
                      step_time_text(mean).c_str());
      }
      labelled_plot(ps, "ms_plot", title, ms, 1.0f, "%.3g ms");
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
}

// What the lecture teaches, on the triangles (core/triangle_fields.h), in one row: the
// colouring, the principal-stress glyphs, the energy landscape's window.
void color_by_row(PanelState& ps) {
  static const char* const kFields[] = {"colour: det F", "colour: ψ", "colour: stress",
                                        "colour: clamped"};
  int field = static_cast<int>(ps.color_by);
  ImGui::SetNextItemWidth(150.0f * ps.ui_scale);
  if (ImGui::Combo("##color_by", &field, kFields, IM_ARRAYSIZE(kFields)))
    ps.color_by = static_cast<TriangleField>(field);
  remember(ps, "color_by");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "what colours the triangles: det F; ψ, the energy density; the principal Cauchy "
        "stress of largest magnitude (tension red, compression blue); or how many of ∂P/∂F's "
        "eigenvalues the PSD projection clamps");
  ImGui::SameLine();
  ImGui::Checkbox("glyphs", &ps.stress_glyphs);
  remember(ps, "stress_glyphs");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("principal stresses: a pair of strokes per triangle, length by magnitude");
  ImGui::SameLine();
  ImGui::Checkbox("landscape", &ps.show_landscape);
  remember(ps, "landscape");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "the energy landscape: ψ over the singular values (σ₁, σ₂), every triangle a dot");
}

// The view: UI scale, where the det F panel goes, the det F colour scale, the colouring.
void view_section(PanelState& ps) {
  // Applied when released (fonts are rebuilt), in steps of 0.25.
  float scale = ps.ui_scale_edit > 0.0f ? ps.ui_scale_edit : ps.ui_scale;
  char shown[16];
  std::snprintf(shown, sizeof shown, "%.2f", scale);
  slider_with_readable_value(
      "UI scale", (scale - kMinUiScale) / (kMaxUiScale - kMinUiScale), shown,
      [&] { return ImGui::SliderFloat("UI scale", &scale, kMinUiScale, kMaxUiScale, "%.2f"); });
  remember(ps, "ui_scale");
  if (ImGui::IsItemActive()) ps.ui_scale_edit = scale;
  if (ImGui::IsItemDeactivated()) {
    ps.ui_scale_edit = -1.0f;
    ps.ui_scale = std::clamp(std::round(scale * 4.0f) / 4.0f, kMinUiScale, kMaxUiScale);
  } else if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("text and panels larger for the back row (keys + and -)");
  }
  // One row: where the det F panel goes, and its colour scale.
  const float half = 0.5f * (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x);
  const char* modes[] = {"det F panel beside", "det F panel over", "det F panel hidden"};
  int mode = static_cast<int>(ps.det_f_panel);
  ImGui::SetNextItemWidth(half);
  if (ImGui::Combo("##det_f_panel", &mode, modes, 3))
    ps.det_f_panel = static_cast<render::PanelMode>(mode);
  remember(ps, "det_f_panel");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the det F panel: beside the picture, over it, or hidden (key D)");
  ImGui::SameLine();
  const char* ranges[] = {"colours 0.25 to 4", "colours: auto, run", "colours: auto, frame"};
  int range = static_cast<int>(ps.color_range);
  ImGui::SetNextItemWidth(half);
  if (ImGui::Combo("##colours", &range, ranges, 3))
    ps.color_range = static_cast<render::ColorRangeMode>(range);
  remember(ps, "colours");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "det F colour scale: fixed 0.25 to 4, or symmetric in log det F around 1 "
        "from the run so far or from this frame (key C); ψ and stress: the widest range "
        "so far (fixed, run) or this frame's");
  color_by_row(ps);
}

// The closed panel's button, a finger high, at the window's top left. True when tapped.
bool panel_open_button(PanelState& ps, ImVec2 at) {
  ImGui::SetNextWindowPos(at, ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##open_panel", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  const bool tapped = ImGui::Button("Controls", ImVec2(0, kTouchTarget * ps.ui_scale));
  remember(ps, "panel_toggle");
  ImGui::End();
  return tapped;
}

}  // namespace

PanelRequests draw_panel(LiveController& lc, PanelState& ps) {
  PanelRequests req;
  ps.previous_rects.swap(ps.rects);
  ps.rects.clear();
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const PanelPlacement place = place_panel(vp->WorkSize.x, vp->WorkSize.y, ps.ui_scale, ps.visible);
  const bool button = ps.touch || place.drawer;  // a visible open/close button
  if (!ps.visible) {
    if (button) req.toggle_panel = panel_open_button(ps, vp->WorkPos);
    return req;
  }
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + place.x, vp->WorkPos.y + place.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(place.w, place.h), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(1.0f);  // opaque: the picture's plane lines must not show through
  // A scroll bar a finger can drag where the panel is longer than the screen.
  if (ps.touch) ImGui::PushStyleVar(ImGuiStyleVar_ScrollbarSize, 0.5f * kTouchTarget * ps.ui_scale);
  // No title bar: the window's own says "invfree live", and at 1280x720 the panel's rows
  // need its height (every control inside the window, none behind the scroll bar).
  ImGui::Begin("invfree live", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
  if (ps.touch) ImGui::PopStyleVar();
  ps.rects["panel"] = {place.x, place.y, place.x + place.w, place.y + place.h};
  ImGui::PushItemWidth(place.w * 0.55f);
  if (button) {
    if (ImGui::Button("Hide controls", ImVec2(0, kTouchTarget * ps.ui_scale)))
      req.toggle_panel = true;
    remember(ps, "panel_toggle");
    ImGui::SameLine();
    ImGui::AlignTextToFramePadding();
    ImGui::TextColored(kDimColor, "F1: keys    Tab: hide");
  } else {
    ImGui::TextColored(kDimColor, "F1: keys and mouse    Tab: hide this panel");
  }
  playback_section(lc, ps, req);
  ImGui::Separator();
  scene_section(lc, ps);
  ImGui::Separator();
  material_section(lc, ps);
  ImGui::Separator();
  solver_section(lc, ps);
  ImGui::Separator();
  contact_section(lc, ps);
  ImGui::Separator();
  view_section(ps);
  ImGui::Separator();
  stats_section(lc, ps);
  ImGui::PopItemWidth();
  ImGui::End();
  return req;
}

// Where the banners begin: 16 px into the picture, and below the panel's controls where they
// lie over it (the page's closed panel's button; an open drawer's rows), never over them.
float banners_top(const PanelState& ps, const WidgetRect& area) {
  float y = area.y0 + 16.0f;
  for (const auto& [name, r] : ps.rects)
    if (name != "panel" && name != "picture" && name != "note" && name != "inspector" &&
        r.x1 > area.x0 && r.x0 < area.x1)
      y = std::max(y, r.y1 + 8.0f);
  return y;
}

void draw_banners(const LiveController& lc, PanelState& ps, const WidgetRect& area) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float cx = 0.5f * (area.x0 + area.x1);
  float y = banners_top(ps, area);
  ImFont* big = ps.big_font ? ps.big_font : ImGui::GetFont();
  const float big_size = big->FontSize;
  // An open drawer over the picture (a phone): its Play button says it; PAUSED below its
  // rows would push a note off the screen.
  const auto drawer = ps.rects.find("panel");
  const bool over_picture = drawer != ps.rects.end() && drawer->second.x1 > area.x0;
  if (!lc.playing() && !over_picture) {
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
    y = b.y + 8.0f;
  }
  if (!lc.note.empty()) {  // yellow, over the picture: the panel's controls stay put
    const float wrap = std::min(area.x1 - area.x0 - 40.0f, 720.0f * ps.ui_scale);
    ImFont* f = ImGui::GetFont();
    const ImVec2 sz = f->CalcTextSizeA(ImGui::GetFontSize(), FLT_MAX, wrap, lc.note.c_str());
    const ImVec2 a(cx - 0.5f * sz.x - 12.0f, y), b(cx + 0.5f * sz.x + 12.0f, y + sz.y + 12.0f);
    dl->AddRectFilled(a, b, IM_COL32(40, 34, 10, 225), 6.0f);
    dl->AddText(f, ImGui::GetFontSize(), ImVec2(a.x + 12.0f, a.y + 6.0f),
                ImGui::ColorConvertFloat4ToU32(kNoteColor), lc.note.c_str(), nullptr, wrap);
    ps.rects["note"] = {a.x, a.y, b.x, b.y};
  }
  if (!ps.last_output.empty()) {  // the last screenshot / recording line, at the bottom
    const float fs = ImGui::GetFontSize();
    const ImVec2 p(area.x0 + 10.0f, area.y1 - fs - 10.0f);
    const ImVec2 sz = ImGui::CalcTextSize(ps.last_output.c_str());
    dl->AddRectFilled(ImVec2(p.x - 6.0f, p.y - 4.0f), ImVec2(p.x + sz.x + 6.0f, p.y + fs + 4.0f),
                      IM_COL32(30, 30, 30, 200), 4.0f);
    dl->AddText(p, IM_COL32(235, 235, 235, 255), ps.last_output.c_str());
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
