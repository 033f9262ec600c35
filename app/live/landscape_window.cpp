#include "app/live/landscape_window.h"

#include <imgui.h>

namespace invfree::live {

void draw_landscape_window(const Simulation& sim, int selected, PanelState& ps,
                           LandscapePanelCache& cache) {
  if (!ps.show_landscape) return;
  const float w = 270.0f * ps.ui_scale;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(
      ImVec2(vp->WorkPos.x + vp->WorkSize.x - 8.0f, vp->WorkPos.y + vp->WorkSize.y - 8.0f),
      ImGuiCond_Appearing, ImVec2(1.0f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(w, 0.0f), ImGuiCond_Always);  // 0: fit the height
  ImGui::SetNextWindowBgAlpha(0.97f);  // over the colour bar: its ticks must not show through
  if (ImGui::Begin("Energy landscape", &ps.show_landscape, ImGuiWindowFlags_NoSavedSettings)) {
    if (sim.scene.has_triangle_elasticity()) {
      const float inner = ImGui::GetContentRegionAvail().x;
      draw_landscape_panel(sim, selected, ImVec2(inner, 1.2f * inner), cache);
    } else {
      ImGui::TextWrapped("n/a: a mass-spring scene has no energy density over singular values");
    }
  }
  const ImVec2 a = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  ps.rects["landscape_window"] = {a.x, a.y, a.x + s.x, a.y + s.y};
  ImGui::End();
}

}  // namespace invfree::live
