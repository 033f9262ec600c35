#include "app/live/auto_fit_view.h"

#include <algorithm>

#include "app/body_extent.h"
namespace invfree::live {

void AutoFitView::fit_box(const LiveController& lc, const render::PixelRect& visible,
                          bool bodies) {
  render::WorldBox b = render::scene_world_box(lc.settings());
  const VecX& x = lc.simulation().x;
  if (x.size() >= 2) {
    render::WorldBox nodes{x[0], x[0], x[1], x[1]};
    for (Eigen::Index i = 0; i + 1 < x.size(); i += 2) {
      nodes = {std::min(nodes.x0, x[i]), std::max(nodes.x1, x[i]), std::min(nodes.y0, x[i + 1]),
               std::max(nodes.y1, x[i + 1])};
    }
    const double pad = 0.15 * std::max({nodes.x1 - nodes.x0, nodes.y1 - nodes.y0,
                                        0.1 * scene_length_scale(lc.settings())});
    nodes = {nodes.x0 - pad, nodes.x1 + pad, nodes.y0 - pad, nodes.y1 + pad};
    if (bodies)
      b = nodes;
    else
      b = {std::min(b.x0, nodes.x0), std::max(b.x1, nodes.x1), std::min(b.y0, nodes.y0),
           std::max(b.y1, nodes.y1)};
  }
  auto_fit_ = true;
  bodies_ = bodies;
  view_.fit({b.x0, b.y0, b.x1, b.y1}, visible.x, visible.y, visible.w, visible.h);
  mesh_generation_ = lc.mesh_generation();
}

// The follow camera's next view: the bodies (render's FollowCamera), eased from the last.
void AutoFitView::follow_step(const LiveController& lc, const render::PixelRect& visible) {
  const Simulation& sim = lc.simulation();
  if (sim.x.size() < 2) return fit_box(lc, visible, false);  // nothing to follow
  const render::Camera c = camera_.next(sim.x, sim.scene, visible);
  view_.pixels_per_metre = c.pixels_per_metre;
  view_.center = c.to_world(Vec2(0.5 * view_.width, 0.5 * view_.height));
  mesh_generation_ = lc.mesh_generation();
  restarts_ = lc.restarts();
}

void AutoFitView::fit(const LiveController& lc, const render::PixelRect& visible) {
  if (!follow_) return fit_box(lc, visible, false);
  auto_fit_ = true;
  bodies_ = false;
  camera_.last.reset();  // a jump, not an easing from elsewhere
  follow_step(lc, visible);
}

void AutoFitView::fit_bodies(const LiveController& lc, const render::PixelRect& visible) {
  if (follow_)
    fit(lc, visible);
  else
    fit_box(lc, visible, true);
}

void AutoFitView::refit(const LiveController& lc, const render::PixelRect& visible) {
  if (!auto_fit_) return;
  if (follow_ && !bodies_)
    fit(lc, visible);
  else
    fit_box(lc, visible, bodies_);
}

void AutoFitView::update(const LiveController& lc, const render::PixelRect& visible) {
  if (lc.mesh_generation() != mesh_generation_) return fit(lc, visible);
  if (!follows()) return;
  if (lc.restarts() != restarts_) return fit(lc, visible);
  if (lc.pulling()) return;
  // Paused, the view goes straight to the bodies: a still picture is the same whenever it is
  // drawn (the easing of a run played frame by frame would leave it wherever the frames
  // between two Step clicks had got it).
  if (!lc.playing()) camera_.last.reset();
  follow_step(lc, visible);
}

void AutoFitView::set_size(int width, int height) {
  view_.width = width;
  view_.height = height;
}

void AutoFitView::pan(double dx, double dy) {
  view_.pan(dx, dy);
  auto_fit_ = false;
}

void AutoFitView::zoom_at(const Vec2& pixel, double factor) {
  view_.zoom_at(pixel, factor);
  auto_fit_ = false;
}

}  // namespace invfree::live
