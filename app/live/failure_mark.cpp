#include "app/live/failure_mark.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace invfree::live {

void draw_failure_mark(const LiveController& lc, const WidgetRect& area) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImU32 red = IM_COL32(220, 30, 40, 255);
  const float t = std::max(6.0f, 0.012f * (area.y1 - area.y0));  // the frame's thickness
  dl->AddRect(ImVec2(area.x0 + 0.5f * t, area.y0 + 0.5f * t),
              ImVec2(area.x1 - 0.5f * t, area.y1 - 0.5f * t), red, 0.0f, 0, t);
  char stamp[96];
  std::snprintf(stamp, sizeof stamp, "STEP %ld FAILED - the last good state (t = %.3f s)",
                lc.simulation().step_count + 1, lc.simulation().time);
  ImFont* f = ImGui::GetFont();
  const float size = 1.25f * ImGui::GetFontSize();
  const ImVec2 sz = f->CalcTextSizeA(size, FLT_MAX, 0.0f, stamp);
  const float cx = 0.5f * (area.x0 + area.x1);
  const ImVec2 a(cx - 0.5f * sz.x - 14.0f, area.y1 - t - sz.y - 22.0f);
  const ImVec2 b(cx + 0.5f * sz.x + 14.0f, area.y1 - t - 8.0f);
  dl->AddRectFilled(a, b, red, 4.0f);
  dl->AddText(f, size, ImVec2(a.x + 14.0f, a.y + 7.0f), IM_COL32(255, 255, 255, 255), stamp);
}

}  // namespace invfree::live
