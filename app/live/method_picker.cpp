#include "app/live/method_picker.h"

#include <imgui.h>

#include <string>

#include "app/live/method_choice.h"
#include "app/render/frame_text.h"

namespace invfree::live {

void method_row(LiveController& lc, PanelState& ps) {
  const SceneDef& s = lc.settings();
  const Method* current = current_method(s);
  const char* shown = "other (the model picker's)";
  for (const LiveMethod& m : live_methods())
    if (current && std::string(current->name) == m.name) shown = m.label;
  if (ImGui::BeginCombo("##method", shown)) {
    for (const LiveMethod& m : live_methods()) {
      const bool is_current = current && std::string(current->name) == m.name;
      const bool chosen = ImGui::Selectable(m.label, is_current);
      ps.rects[std::string("method:") + m.name] = {
          ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y, ImGui::GetItemRectMax().x,
          ImGui::GetItemRectMax().y};
      if (chosen && !is_current) {
        SceneDef next;
        if (const std::string e = switch_method(s, *find_method(m.name), &next); !e.empty())
          lc.note = "not applied: " + e;
        else if (lc.restart_with(next))
          lc.note = std::string("restarted at t = 0 with ") + m.label;
      }
    }
    ImGui::EndCombo();
  }
  ps.rects["method"] = {ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y,
                        ImGui::GetItemRectMax().x, ImGui::GetItemRectMax().y};
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "the method: %s\n"
        "the lecture's switches (invfree study compares the same methods);\n"
        "switching restarts the scene at t = 0, keeping the other settings",
        solver_caption(s).c_str());
}

bool body_materials_rows(const LiveController& lc, PanelState& ps) {
  const SceneDef& s = lc.settings();
  bool own = false;
  for (const BodyDef& b : s.bodies) own = own || b.lame.has_value();
  if (!own || s.has_mass_spring) return false;
  ImGui::BeginGroup();
  ImGui::TextColored(ImVec4(1.0f, 0.82f, 0.35f, 1.0f),
                     "each body's own material (the sliders set all to one):");
  for (int k = 0; k < body_count(s); ++k) {
    const Lame l = placed_body(s, k).lame;
    ImGui::Text("  body %d: \xce\xbc = %s, \xce\xbb = %s", k + 1,
                render::format_si(l.mu, "Pa").c_str(), render::format_si(l.lambda, "Pa").c_str());
  }
  ImGui::EndGroup();
  ps.rects["body_materials"] = {ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y,
                                ImGui::GetItemRectMax().x, ImGui::GetItemRectMax().y};
  return true;
}

}  // namespace invfree::live
