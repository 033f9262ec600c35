// The mouse over the picture, read from ImGui's io (so injected input acts as a person's
// would): the left button grabs the node under the pointer and pulls it with the grab
// spring while held, or pans where no node is near; the right or middle button pans; the
// wheel zooms about the pointer. Over the panel the mouse belongs to ImGui. Also what the
// gestures show over the picture: the spring while pulling, and a ring on the node a click
// would grab.
// A left press released within kClickSlop pixels of where it went down is also a click
// (whatever it grabbed or panned meanwhile, a few pixels' worth): handle() returns its
// world point, where the live window picks the triangle to inspect.
#pragma once

#include <imgui.h>

#include <optional>

#include "app/live/auto_fit_view.h"
#include "app/live/live_controller.h"
#include "app/render/camera.h"

namespace invfree::live {

// How far (window pixels) a press may wander and still be a click, not a drag: ImGui's own
// drag threshold (io.MouseDragThreshold's default).
constexpr float kClickSlop = 6.0f;

class MouseGestures {
 public:
  // This frame's mouse, between ImGui::NewFrame and ImGui::Render. `visible`: the part of
  // the picture no panel covers (framebuffer pixels; a pulled body stops at its edge);
  // `ps`: framebuffer pixels per window coordinate. Returns the world point (m) of a
  // left click on the picture that ended this frame.
  std::optional<Vec2> handle(LiveController& lc, AutoFitView& view,
                             const render::PixelRect& visible, double ps);
  // The spring or the hover ring, on ImGui's background draw list.
  void draw_markers(const LiveController& lc, const ViewTransform& view, double ps) const;
  bool dragging() const { return drag_ != Drag::None; }

 private:
  std::optional<Vec2> continue_drag(LiveController& lc, AutoFitView& view,
                                    const render::PixelRect& visible, const Vec2& mouse, double ps);
  void note_pointer(const ImGuiIO& io);

  enum class Drag { None, Pan, Pull } drag_ = Drag::None;
  Vec2 last_mouse_ = Vec2::Zero();
  // The left press that started this drag, while it can still end as a click.
  bool click_possible_ = false;
  ImVec2 press_pos_;
  // The ring shows only once the pointer has moved: a still pointer under Xvfb would ring
  // whatever node lies under it in every scripted screenshot.
  bool pointer_moved_ = false;
  bool pointer_seen_ = false;
  ImVec2 pointer_start_;
};

}  // namespace invfree::live
