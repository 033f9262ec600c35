// The mouse over the picture, read from ImGui's io (so injected input acts as a person's
// would): the left button grabs the node under the pointer and pulls it with the grab
// spring while held, or pans where no node is near; the right or middle button pans; the
// wheel zooms about the pointer. Over the panel the mouse belongs to ImGui. Also what the
// gestures show over the picture: the spring while pulling, and a ring on the node a click
// would grab.
#pragma once

#include <imgui.h>

#include "app/live/auto_fit_view.h"
#include "app/live/live_controller.h"
#include "app/render/camera.h"

namespace invfree::live {

class MouseGestures {
 public:
  // This frame's mouse, between ImGui::NewFrame and ImGui::Render. `visible`: the part of
  // the picture no panel covers (framebuffer pixels; a pulled body stops at its edge);
  // `ps`: framebuffer pixels per window coordinate.
  void handle(LiveController& lc, AutoFitView& view, const render::PixelRect& visible, double ps);
  // The spring or the hover ring, on ImGui's background draw list.
  void draw_markers(const LiveController& lc, const ViewTransform& view, double ps) const;
  bool dragging() const { return drag_ != Drag::None; }

 private:
  void continue_drag(LiveController& lc, AutoFitView& view, const render::PixelRect& visible,
                     const Vec2& mouse, double ps);
  void note_pointer(const ImGuiIO& io);

  enum class Drag { None, Pan, Pull } drag_ = Drag::None;
  Vec2 last_mouse_ = Vec2::Zero();
  // The ring shows only once the pointer has moved: a still pointer under Xvfb would ring
  // whatever node lies under it in every scripted screenshot.
  bool pointer_moved_ = false;
  bool pointer_seen_ = false;
  ImVec2 pointer_start_;
};

}  // namespace invfree::live
