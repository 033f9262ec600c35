// The live window's view of the world (view_transform.h) and the rule that keeps it
// framed: it fits the scene's stage and its bodies (a body may start outside the stage, as
// course-1's stretched square does) at the start and for each new scene or mesh, and fits
// again (the stage, or the bodies after F) when the window, the panel or the UI scale
// changes, until the user pans or zooms; a person who chose a view keeps it.
#pragma once

#include "app/live/live_controller.h"
#include "app/live/view_transform.h"
#include "app/render/camera.h"

namespace invfree::live {

class AutoFitView {
 public:
  const ViewTransform& transform() const { return view_; }

  // `visible`: the part of the frame the world shows in and no panel covers (framebuffer
  // pixels). Fits the scene's stage, or with `bodies` every node with a margin (F).
  void fit(const LiveController& lc, const render::PixelRect& visible, bool bodies = false);
  // The layout changed: fits again as last time unless the user has moved the view.
  void refit(const LiveController& lc, const render::PixelRect& visible);
  // Fits the stage when the scene or its mesh is not the one last fitted.
  void follow_scene(const LiveController& lc, const render::PixelRect& visible);

  void set_size(int width, int height);  // the framebuffer's, pixels
  // The user's moves (pixels); the view stays where they leave it.
  void pan(double dx, double dy);
  void zoom_at(const Vec2& pixel, double factor);

 private:
  ViewTransform view_;
  bool auto_fit_ = true;               // refit on layout changes
  bool bodies_ = false;                // the last fit framed the bodies (F), not the whole stage
  long mesh_generation_ = -1;  // the mesh the last fit showed (a new scene is a new mesh)
};

}  // namespace invfree::live
