#include "app/live/auto_fit_view.h"

#include <algorithm>

#include "app/body_extent.h"
namespace invfree::live {

void AutoFitView::fit(const LiveController& lc, const render::PixelRect& visible, bool bodies) {
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

void AutoFitView::refit(const LiveController& lc, const render::PixelRect& visible) {
  if (auto_fit_) fit(lc, visible, bodies_);
}

void AutoFitView::follow_scene(const LiveController& lc, const render::PixelRect& visible) {
  if (lc.mesh_generation() != mesh_generation_) fit(lc, visible);
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
