#include "app/live/auto_fit_view.h"

#include <algorithm>

#include "app/body_extent.h"
namespace invfree::live {

void AutoFitView::fit(const LiveController& lc, const render::PixelRect& visible, bool bodies) {
  render::WorldBox b = render::scene_world_box(lc.settings());
  if (bodies) {
    const VecX& x = lc.simulation().x;
    b = {x[0], x[0], x[1], x[1]};
    for (Eigen::Index i = 0; i + 1 < x.size(); i += 2) {
      b = {std::min(b.x0, x[i]), std::max(b.x1, x[i]), std::min(b.y0, x[i + 1]),
           std::max(b.y1, x[i + 1])};
    }
    const double pad =
        0.15 * std::max({b.x1 - b.x0, b.y1 - b.y0, 0.1 * scene_length_scale(lc.settings())});
    b = {b.x0 - pad, b.x1 + pad, b.y0 - pad, b.y1 + pad};
  }
  auto_fit_ = true;
  bodies_ = bodies;
  view_.fit({b.x0, b.y0, b.x1, b.y1}, visible.x, visible.y, visible.w, visible.h);
  scene_index_ = lc.selected_scene();
  n_seg_ = lc.settings().n_seg;
}

void AutoFitView::refit(const LiveController& lc, const render::PixelRect& visible) {
  if (auto_fit_) fit(lc, visible, bodies_);
}

void AutoFitView::follow_scene(const LiveController& lc, const render::PixelRect& visible) {
  if (lc.selected_scene() != scene_index_ || lc.settings().n_seg != n_seg_) fit(lc, visible);
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
