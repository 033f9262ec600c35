#include "app/live/inspector_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/render/frame_text.h"

namespace invfree::live {

namespace {

const ImVec4 kDimColor(0.65f, 0.65f, 0.65f, 1.0f);
const ImU32 kPositiveBar = IM_COL32(90, 150, 230, 255);
const ImU32 kNegativeBar = IM_COL32(235, 60, 60, 255);
const ImVec4 kNegativeText(1.0f, 0.42f, 0.42f, 1.0f);

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}
std::string stress(double v) {
  return render::format_si(v, "Pa");
}

// One row of the values table: a name, then up to two cells.
void row(const char* name, const std::string& a, const std::string& b = "") {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(name);
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(a.c_str());
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(b.c_str());
}

// A 2x2 matrix as two rows, the name on the first.
template <class Format>
void matrix(const char* name, const Mat2& m, Format format) {
  row(name, format(m(0, 0)), format(m(0, 1)));
  row("", format(m(1, 0)), format(m(1, 1)));
}

void values_table(const StressAnalysis& a) {
  if (!ImGui::BeginTable("values", 3, ImGuiTableFlags_SizingFixedFit)) return;
  matrix("F", a.F, number);
  matrix("U", a.svd.U, number);
  row("σ", number(a.svd.sigma(0)), number(a.svd.sigma(1)));
  matrix("V", a.svd.V, number);
  row("J", number(a.J));
  row("ψ", std::isfinite(a.psi) ? stress(a.psi) : "+∞");
  if (a.finite) {
    matrix("P", a.P, stress);
    matrix("Cauchy", a.cauchy, stress);
    row("principal", stress(a.principal_stress(0)), stress(a.principal_stress(1)));
  }
  ImGui::EndTable();
}

// The four eigenvalues of dP/dF as horizontal bars about a zero line (one scale: the
// largest magnitude), with their names and values; a negative one is red, and the value the
// projection sets in its place (0) follows it.
void eigenvalue_bars(const StressAnalysis& a, float scale) {
  ImGui::TextUnformatted("eigenvalues of ∂P/∂F");
  double largest = 0.0;
  for (int k = 0; k < 4; ++k) largest = std::max(largest, std::fabs(a.eigenvalues(k)));
  const float name_w = ImGui::CalcTextSize("scale 2 ").x;
  const float bar_w = 110.0f * scale, h = ImGui::GetTextLineHeight();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (int k = 0; k < 4; ++k) {
    const double e = a.eigenvalues(k);
    const bool negative = e < 0.0;
    ImGui::TextUnformatted(kEigenvalueNames[k]);
    ImGui::SameLine(name_w + ImGui::GetStyle().WindowPadding.x);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(bar_w, h));
    const float mid = p.x + 0.5f * bar_w;
    const float len =
        largest > 0.0 ? static_cast<float>(0.5 * bar_w * std::fabs(e) / largest) : 0.0f;
    const float x0 = negative ? mid - len : mid, x1 = negative ? mid : mid + len;
    // At least a sliver: a small negative eigenvalue beside a large one is still seen red.
    dl->AddRectFilled(ImVec2(negative ? std::min(x0, mid - 3.0f) : x0, p.y + 0.15f * h),
                      ImVec2(negative ? x1 : std::max(x1, x0 + 1.0f), p.y + 0.85f * h),
                      negative ? kNegativeBar : kPositiveBar);
    dl->AddLine(ImVec2(mid, p.y), ImVec2(mid, p.y + h), ImGui::GetColorU32(ImGuiCol_Text));
    ImGui::SameLine();
    if (negative)
      ImGui::TextColored(kNegativeText, "%s", stress(e).c_str());
    else
      ImGui::TextUnformatted(stress(e).c_str());
    if (a.projected_eigenvalues(k) != e) {
      ImGui::SameLine();
      ImGui::TextColored(kDimColor, "→ %s", stress(a.projected_eigenvalues(k)).c_str());
    }
  }
}

void inspector_contents(const Inspected& in, float scale) {
  const StressAnalysis& a = in.analysis;
  ImGui::Text("triangle %d, step %ld", in.triangle, in.step);
  if (!in.elastic) {
    ImGui::TextWrapped(
        "n/a: a mass-spring scene (its springs carry the forces; the triangles have no "
        "elasticity to inspect)");
    return;
  }
  ImGui::Text("%s   μ %s   λ %s", render::model_display_name(a.model), stress(a.lame.mu).c_str(),
              stress(a.lame.lambda).c_str());
  values_table(a);
  if (!a.finite) {
    ImGui::TextWrapped("inverted: ψ is +∞ here, no P and no Hessian");
    return;
  }
  eigenvalue_bars(a, scale);
  ImGui::Text("clamped: %d of 4", a.clamped);
  ImGui::Text("FD check: P %.1e   ∂P/∂F %.1e", in.fd.P, in.fd.dPdF);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "relative difference from central differences of ψ alone (as invfree inspect)");
}

}  // namespace

bool draw_inspector(const Inspected& inspected, PanelState& ps, const WidgetRect& area, bool left,
                    bool over_picture) {
  const float scale = ps.ui_scale;
  ImGui::SetNextWindowPos(ImVec2(left ? area.x0 + 8.0f : area.x1 - 8.0f, area.y0 + 8.0f),
                          ps.place_inspector ? ImGuiCond_Always : ImGuiCond_Appearing,
                          ImVec2(left ? 0.0f : 1.0f, 0.0f));
  ps.place_inspector = false;
  // Wide enough for a clamped eigenvalue's "-50.8 kPa -> 0 Pa"; 0: fit the height.
  ImGui::SetNextWindowSize(ImVec2(316.0f * scale, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(over_picture ? 0.88f : 1.0f);
  bool open = true;
  if (ImGui::Begin("Inspector", &open, ImGuiWindowFlags_NoSavedSettings)) {
    inspector_contents(inspected, scale);
  }
  const ImVec2 a = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  ps.rects["inspector"] = {a.x, a.y, a.x + s.x, a.y + s.y};
  ImGui::End();
  return open;
}

}  // namespace invfree::live
