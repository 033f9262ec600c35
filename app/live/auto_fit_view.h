// The live window's view of the world (view_transform.h) and the rule that keeps it
// framed. Two defaults: the follow camera (`invfree live`'s and the page's: render's
// FollowCamera, app/render/view_choices.h, on the bodies with a third of their size around
// them, eased frame to frame and never letting a node leave the picture; it jumps to the
// bodies at the start, for each new scene or mesh, on a reset and when the layout changes),
// or the whole stage (--camera fixed: the scene's stage and its bodies -- a body may start
// outside the stage, as course-1's stretched square does -- fitted at the start and for
// each new scene or mesh, again when the window, the panel or the UI scale changes). The
// user's pan or zoom takes over: a person who chose a view keeps it until F (which goes
// back to following, or with the fixed camera frames the bodies) or a new scene.
#pragma once

#include "app/live/live_controller.h"
#include "app/live/view_transform.h"
#include "app/render/camera.h"
#include "app/render/view_choices.h"

namespace invfree::live {

class AutoFitView {
 public:
  const ViewTransform& transform() const { return view_; }

  // The default camera: following the bodies (true) or the whole stage.
  void set_follow(bool on) { follow_ = on; }
  bool follows() const { return follow_ && auto_fit_ && !bodies_; }

  // `visible`: the part of the frame the world shows in and no panel covers (framebuffer
  // pixels). The default view (the follow camera's jump to the bodies, or the stage).
  void fit(const LiveController& lc, const render::PixelRect& visible);
  // F: back to following the bodies, or (fixed camera) every node with a margin.
  void fit_bodies(const LiveController& lc, const render::PixelRect& visible);
  // The layout changed: fits again as last time unless the user has moved the view.
  void refit(const LiveController& lc, const render::PixelRect& visible);
  // Each frame: the default view when the scene or its mesh is not the one last fitted (even
  // after the user chose a view), and the follow camera's next step (not while a node is
  // grabbed: the cursor's world point stays put under the hand; paused, straight to the
  // bodies).
  void update(const LiveController& lc, const render::PixelRect& visible);

  void set_size(int width, int height);  // the framebuffer's, pixels
  // The user's moves (pixels); the view stays where they leave it.
  void pan(double dx, double dy);
  void zoom_at(const Vec2& pixel, double factor);

 private:
  void fit_box(const LiveController& lc, const render::PixelRect& visible, bool bodies);
  void follow_step(const LiveController& lc, const render::PixelRect& visible);

  ViewTransform view_;
  bool follow_ = false;        // the default camera follows the bodies
  bool auto_fit_ = true;       // refit on layout changes (the user has not moved the view)
  bool bodies_ = false;        // the fixed camera's last fit framed the bodies (F)
  long mesh_generation_ = -1;  // the mesh the last fit showed (a new scene is a new mesh)
  long restarts_ = -1;         // the run the follow camera followed (a reset jumps back)
  render::FollowCamera camera_;
};

}  // namespace invfree::live
