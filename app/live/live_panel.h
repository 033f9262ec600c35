// The live window's Dear ImGui panel: playback, scene and model pickers, the material
// (log sliders for mu and lambda, E and nu editable beside them), solver and contact
// settings, the grab spring, the statistics with plots of the last steps, and the output
// buttons. Every edit goes through LiveController::apply with the limits of
// param_limits.h; a clamped or refused edit shows its note at the top of the panel.
// The view section also picks what the triangles are coloured by (det F, Psi, stress,
// clamped), the principal-stress glyphs and the energy landscape's window.
// Also the F1 help overlay and the PAUSED / failure / note banners.
// Sliders show their value in the half of the slider the handle is not in, and Ctrl+click
// types a value into any of them.
// Inputs: the controller and the panel's own state. Output: what the window must do
// (screenshot, record, fit the view, quit). Call between ImGui::NewFrame and ImGui::Render.
#pragma once

#include <map>
#include <string>

#include "app/live/live_app.h"
#include "app/live/live_controller.h"
#include "app/render/camera.h"
#include "app/render/view_choices.h"
#include "triangle_fields.h"

struct ImFont;

namespace invfree::live {

struct PanelState {
  bool visible = true;
  bool show_help = false;
  // Touch controls (the web page): a button that opens and closes the panel, a taller n_seg
  // row with -/+ buttons (panel_layout.h).
  bool touch = false;
  float width = 390.0f;  // pixels, at UI scale 1
  // The view choices the panel edits and the window applies: the UI scale (panel and
  // det F panel together), where the det F panel goes, the det F colour scale.
  float ui_scale = 1.0f;
  float ui_scale_edit = -1.0f;  // the UI scale slider's value while it is being dragged
  render::PanelMode det_f_panel = render::PanelMode::Side;
  render::ColorRangeMode color_range = render::ColorRangeMode::Fixed;
  // What the triangles are coloured by (det F as before), the principal-stress glyphs, and
  // the energy landscape's window.
  TriangleField color_by = TriangleField::DetF;
  bool stress_glyphs = false;
  bool show_landscape = false;
  bool place_inspector = false;  // a triangle was just picked: the inspector goes beside it
  // Ctrl+click on a slider types its value: the slider's name while typing, the field's
  // value and the frames it has been open (focus arrives a frame later).
  std::string typing;
  double typed = 0.0;
  int typing_frames = 0;
  std::map<std::string, WidgetRect> previous_rects;  // last frame's (Ctrl+click targets)
  int max_segments = kDefaultMaxSegments;
  int n_seg_edit = -1;  // the n_seg slider's value while it is being dragged
  bool recording = false;
  std::string last_output;                  // e.g. "saved shots/invfree_0003.png"
  ImFont* big_font = nullptr;               // banners
  std::map<std::string, WidgetRect> rects;  // this frame's widget rectangles
};

struct PanelRequests {
  bool screenshot = false;
  bool toggle_record = false;
  bool fit_view = false;
  bool quit = false;
  bool toggle_panel = false;  // the panel's open/close button (as Tab)
};

PanelRequests draw_panel(LiveController& lc, PanelState& ps);

// Banners over the picture: PAUSED, the failed step's message, the note of a clamped or
// refused edit (over the picture, so that it moves no control), REC, and the last output
// line at the bottom. `area` is the part of the window the picture shows in (x0, y0, x1,
// y1, pixels).
void draw_banners(const LiveController& lc, PanelState& ps, const WidgetRect& area);

// The F1 overlay listing every key and mouse gesture (key_bindings.h).
void draw_help_overlay(PanelState& ps);

}  // namespace invfree::live
