#include "app/live/presentation.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "app/live/real_time_rate.h"

namespace invfree::live {

void draw_presentation_readouts(const LiveController& lc, PanelState& ps, const WidgetRect& area,
                                std::optional<double> real_time_rate, const std::string& caption) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  ImFont* big = ps.big_font ? ps.big_font : ImGui::GetFont();
  // A twelfth of the picture's height per line at least: legible from a hall's back row.
  const float size = std::max(big->FontSize, (area.y1 - area.y0) / 12.0f);
  const float small = 0.45f * size;
  const Simulation& sim = lc.simulation();
  const StateStats& st = lc.stats();
  char t[48], det[64], inv[48];
  std::snprintf(t, sizeof t, "t = %.2f s", sim.time);
  const bool triangles = sim.mesh.triangle_count() > 0;
  if (triangles) {
    std::snprintf(det, sizeof det, "min det F = %.3f", st.min_det_f);
    std::snprintf(inv, sizeof inv, "%d inverted", st.inverted);
  } else {
    std::snprintf(det, sizeof det, "no triangles");
    inv[0] = '\0';
  }
  const std::string rate = real_time_rate ? RealTimeRate::text(*real_time_rate) : "";
  const std::string under = caption + (rate.empty() ? "" : "   " + rate);
  float w = 0.0f;
  for (const char* line : {t, det, inv})
    w = std::max(w, big->CalcTextSizeA(size, FLT_MAX, 0.0f, line).x);
  w = std::max(w, big->CalcTextSizeA(small, FLT_MAX, 0.0f, under.c_str()).x);
  const float pad = 0.3f * size;
  const int lines = inv[0] ? 3 : 2;
  const ImVec2 a(area.x0 + pad, area.y0 + pad);
  const ImVec2 b(a.x + w + 2.0f * pad, a.y + lines * size + small + 2.0f * pad);
  dl->AddRectFilled(a, b, IM_COL32(20, 20, 20, 190), 0.2f * size);
  float y = a.y + pad;
  dl->AddText(big, size, ImVec2(a.x + pad, y), IM_COL32(255, 255, 255, 255), t);
  y += size;
  const bool low = triangles && st.min_det_f < 0.5;
  dl->AddText(big, size, ImVec2(a.x + pad, y),
              low ? IM_COL32(255, 190, 90, 255) : IM_COL32(255, 255, 255, 255), det);
  y += size;
  if (inv[0]) {
    dl->AddText(big, size, ImVec2(a.x + pad, y),
                st.inverted > 0 ? IM_COL32(255, 80, 80, 255) : IM_COL32(140, 230, 140, 255), inv);
    y += size;
  }
  dl->AddText(big, small, ImVec2(a.x + pad, y), IM_COL32(220, 220, 220, 255), under.c_str());
  ps.rects["presentation"] = {a.x, a.y, b.x, b.y};
}

void draw_real_time_rate(double rate, const WidgetRect& area) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const std::string text = RealTimeRate::text(rate);
  const float fs = ImGui::GetFontSize();
  const ImVec2 sz = ImGui::CalcTextSize(text.c_str());
  const ImVec2 p(area.x1 - sz.x - 16.0f, area.y1 - fs - 10.0f);
  dl->AddRectFilled(ImVec2(p.x - 6.0f, p.y - 4.0f), ImVec2(p.x + sz.x + 6.0f, p.y + fs + 4.0f),
                    IM_COL32(30, 30, 30, 200), 4.0f);
  dl->AddText(p, IM_COL32(235, 235, 235, 255), text.c_str());
}

}  // namespace invfree::live
