#include "app/live/mouse_gestures.h"

#include <algorithm>
#include <cmath>

namespace invfree::live {

namespace {

constexpr double kGrabRadiusPixels = 14.0;

}  // namespace

std::optional<Vec2> MouseGestures::handle(LiveController& lc, AutoFitView& view,
                                          const render::PixelRect& visible, double ps) {
  const ImGuiIO& io = ImGui::GetIO();
  const Vec2 mouse(io.MousePos.x * ps, io.MousePos.y * ps);
  if (drag_ != Drag::None) return continue_drag(lc, view, visible, mouse, ps);
  const bool mouse_valid = ImGui::IsMousePosValid();
  if (mouse_valid) note_pointer(io);
  if (io.WantCaptureMouse || !mouse_valid) return std::nullopt;
  const ViewTransform& v = view.transform();
  if (io.MouseWheel != 0.0f) view.zoom_at(mouse, std::pow(1.15, io.MouseWheel));
  click_possible_ = false;
  if (io.MouseClicked[0]) {
    click_possible_ = true;
    press_pos_ = io.MousePos;
    const int node =
        lc.nearest_node(v.to_world(mouse), kGrabRadiusPixels * ps / v.pixels_per_metre);
    if (node >= 0) {
      lc.begin_pull(node, v.to_world(mouse));
      drag_ = Drag::Pull;
    } else {
      drag_ = Drag::Pan;
    }
  } else if (io.MouseClicked[1] || io.MouseClicked[2]) {
    drag_ = Drag::Pan;
  }
  last_mouse_ = mouse;
  return std::nullopt;
}

// A drag lasts while its button is held (any button for a pan) and the pointer is in the
// window. A left one that never left kClickSlop of its press ends as a click there.
std::optional<Vec2> MouseGestures::continue_drag(LiveController& lc, AutoFitView& view,
                                                 const render::PixelRect& visible,
                                                 const Vec2& mouse, double ps) {
  const ImGuiIO& io = ImGui::GetIO();
  const bool held = drag_ == Drag::Pull ? io.MouseDown[0]
                                        : (io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2]);
  const bool valid = ImGui::IsMousePosValid();
  if (valid && std::hypot(io.MousePos.x - press_pos_.x, io.MousePos.y - press_pos_.y) > kClickSlop)
    click_possible_ = false;
  std::optional<Vec2> click;
  if (!held || !valid) {
    if (drag_ == Drag::Pull) lc.end_pull();
    drag_ = Drag::None;
    if (click_possible_ && valid) click = view.transform().to_world(mouse);
    click_possible_ = false;
  } else if (drag_ == Drag::Pull) {
    // The target stays in the visible part of the picture: a body pulled toward a panel
    // stops at its edge instead of sliding behind it.
    const render::PixelRect& r = visible;
    const double m = 12.0 * ps;
    const Vec2 inside(std::clamp(mouse.x(), r.x + m, std::max(r.x + m, r.x + r.w - m)),
                      std::clamp(mouse.y(), r.y + m, std::max(r.y + m, r.y + r.h - m)));
    lc.move_pull(view.transform().to_world(inside));
  } else {
    view.pan(mouse.x() - last_mouse_.x(), mouse.y() - last_mouse_.y());
  }
  last_mouse_ = mouse;
  return click;
}

void MouseGestures::note_pointer(const ImGuiIO& io) {
  if (!pointer_seen_) pointer_start_ = io.MousePos;
  pointer_seen_ = true;
  if (io.MousePos.x != pointer_start_.x || io.MousePos.y != pointer_start_.y) pointer_moved_ = true;
}

void MouseGestures::draw_markers(const LiveController& lc, const ViewTransform& view,
                                 double ps) const {
  const ImGuiIO& io = ImGui::GetIO();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const Simulation& sim = lc.simulation();
  auto screen = [&](const Vec2& w) {
    const Vec2 s = view.to_screen(w) / ps;
    return ImVec2(static_cast<float>(s.x()), static_cast<float>(s.y()));
  };
  if (lc.pulling()) {
    const ImVec2 a = screen(sim.x.segment<2>(2 * lc.pull_node()));
    const ImVec2 b = screen(lc.pull_target());
    dl->AddLine(a, b, IM_COL32(20, 20, 20, 230), 2.5f);
    dl->AddCircleFilled(a, 5.0f, IM_COL32(250, 170, 0, 255));
    dl->AddCircle(b, 6.0f, IM_COL32(20, 20, 20, 230), 0, 2.0f);
    return;
  }
  if (drag_ != Drag::None || io.WantCaptureMouse || !ImGui::IsMousePosValid() || !pointer_moved_)
    return;
  const Vec2 mouse(io.MousePos.x * ps, io.MousePos.y * ps);
  const int node =
      lc.nearest_node(view.to_world(mouse), kGrabRadiusPixels * ps / view.pixels_per_metre);
  if (node >= 0)
    dl->AddCircle(screen(sim.x.segment<2>(2 * node)), 7.0f, IM_COL32(250, 170, 0, 255), 0, 2.5f);
}

}  // namespace invfree::live
