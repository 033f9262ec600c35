#include "app/live/landscape_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace invfree {

namespace {

ImU32 to_u32(Rgb c, float alpha = 1.0f) {
  auto byte = [](float v) {
    return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  return IM_COL32(byte(c.r), byte(c.g), byte(c.b), byte(alpha));
}

constexpr ImU32 kInk = IM_COL32(26, 26, 31, 255);
constexpr ImU32 kContour = IM_COL32(26, 26, 31, 150);
constexpr ImU32 kDotFill = IM_COL32(13, 84, 242, 255);
constexpr ImU32 kDotEdge = IM_COL32(255, 255, 255, 255);
constexpr ImU32 kDotPinned = IM_COL32(178, 204, 255, 255);
constexpr ImU32 kHatch = IM_COL32(255, 255, 255, 110);

// How many vertices one draw list may still take: 16-bit indices without the backend's
// vertex offsets (the web page's OpenGL ES 3 backend) address 65536 vertices in all.
long vertex_room(const ImDrawList* dl) {
  if (sizeof(ImDrawIdx) > 2 || (dl->Flags & ImDrawListFlags_AllowVtxOffset)) return 1L << 30;
  return 65535L - static_cast<long>(dl->_VtxCurrentIdx);
}

// Screen mapping of the plot: sigma -> pixels.
struct Plot {
  LandscapeDomain d;
  float x0 = 0, y0 = 0, ppu = 1;
  float x(double s1) const { return x0 + static_cast<float>((s1 - d.s1_min) * ppu); }
  float y(double s2) const { return y0 + static_cast<float>((d.s2_max - s2) * ppu); }
  float x1() const { return x(d.s1_max); }
  float y1() const { return y(d.s2_min); }
};

// The grid as one mesh: a vertex per node with its colour (Gouraud between them), two
// triangles per cell; every `stride`-th node when the draw list has little room left.
void heat_map(ImDrawList* dl, const Plot& p, const LandscapeCache& lc,
              const std::vector<ImU32>& colors, long room) {
  const LandscapeGrid& g = lc.grid;
  int stride = 1;
  auto nodes = [&](int s) { return long((g.n1 - 1) / s + 1) * long((g.n2 - 1) / s + 1); };
  while (stride < 16 && nodes(stride) > room) stride *= 2;
  if (nodes(stride) > room) return;
  const int m1 = (g.n1 - 1) / stride + 1, m2 = (g.n2 - 1) / stride + 1;
  const ImVec2 uv = ImGui::GetFontTexUvWhitePixel();
  dl->PrimReserve((m1 - 1) * (m2 - 1) * 6, m1 * m2);
  const ImDrawIdx base = static_cast<ImDrawIdx>(dl->_VtxCurrentIdx);
  for (int b = 0; b < m2; ++b)
    for (int a = 0; a < m1; ++a) {
      const int i = a * stride, j = b * stride;
      dl->PrimWriteVtx(ImVec2(p.x(g.s1(i)), p.y(g.s2(j))), uv,
                       colors[static_cast<size_t>(i + g.n1 * j)]);
    }
  for (int b = 0; b + 1 < m2; ++b)
    for (int a = 0; a + 1 < m1; ++a) {
      const auto v = static_cast<ImDrawIdx>(base + a + m1 * b);
      const auto up = static_cast<ImDrawIdx>(v + m1);
      dl->PrimWriteIdx(v);
      dl->PrimWriteIdx(static_cast<ImDrawIdx>(v + 1));
      dl->PrimWriteIdx(static_cast<ImDrawIdx>(up + 1));
      dl->PrimWriteIdx(v);
      dl->PrimWriteIdx(static_cast<ImDrawIdx>(up + 1));
      dl->PrimWriteIdx(up);
    }
}

void dashed_line(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 col, float thickness) {
  const float len = std::hypot(b.x - a.x, b.y - a.y);
  if (len <= 0.0f) return;
  const ImVec2 u((b.x - a.x) / len, (b.y - a.y) / len);
  for (float t = 0.0f; t < len; t += 10.0f) {
    const float e = std::min(t + 6.0f, len);
    dl->AddLine(ImVec2(a.x + u.x * t, a.y + u.y * t), ImVec2(a.x + u.x * e, a.y + u.y * e), col,
                thickness);
  }
}

}  // namespace

void draw_landscape_panel(Model model, const Lame& lame, std::span<const SigmaPair> points,
                          int selected, ImVec2 size, LandscapePanelCache& cache) {
  size.x = std::max(size.x, 80.0f);
  size.y = std::max(size.y, 80.0f);
  const LandscapeDomain domain = landscape_domain(model);
  if (update_landscape_cache(model, lame, domain, kLandscapePanelPerUnit, &cache.landscape)) {
    const LandscapeCache& lc = cache.landscape;
    cache.node_colors.resize(lc.grid.psi.size());
    for (size_t k = 0; k < lc.grid.psi.size(); ++k)
      cache.node_colors[k] = to_u32(landscape_color(lc.scale, lc.grid.psi[k]));
  }
  const LandscapeCache& lc = cache.landscape;

  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float line = ImGui::GetTextLineHeight();
  const ImU32 text = ImGui::GetColorU32(ImGuiCol_Text);

  // Layout: the title line (the unit in it), the plot (square cells) with the s2 ticks on its
  // left and the s1 ticks under it, and the colour bar either on the right (a wide panel) or
  // under the plot (a narrow one, as the live window's): whichever gives the larger plot.
  std::string title =
      std::string("\u03a8(\u03c3\u2081, \u03c3\u2082) in Pa: ") + model_label(model);
  if (ImGui::CalcTextSize(title.c_str()).x > size.x)  // "stable neo-Hookean" in a narrow window
    title = std::string("\u03a8 in Pa: ") + model_label(model);
  const float bar_w = 9.0f, bar_label = ImGui::CalcTextSize("100k").x;
  const float left = p0.x + ImGui::CalcTextSize("\u22120.5").x + 8.0f;
  const float top = p0.y + line + 6.0f;
  const float x_ticks = line + 4.0f;
  const double w_units = domain.s1_max - domain.s1_min, h_units = domain.s2_max - domain.s2_min;
  const auto fit = [&](float right, float bottom) {
    return std::max(1.0, std::min((right - left) / w_units, (bottom - top) / h_units));
  };
  const double ppu_side = fit(p0.x + size.x - bar_w - bar_label - 14.0f, p0.y + size.y - x_ticks);
  const double ppu_below =
      fit(p0.x + size.x - 6.0f, p0.y + size.y - x_ticks - (6.0f + bar_w + 2.0f + line));
  const bool bar_below = ppu_below > ppu_side;
  Plot p;
  p.d = domain;
  p.x0 = left;
  p.y0 = top;
  p.ppu = static_cast<float>(bar_below ? ppu_below : ppu_side);
  const float X0 = p.x0, Y0 = p.y0, X1 = p.x1(), Y1 = p.y1();
  const float used_h = (Y1 - p0.y) + x_ticks + (bar_below ? 6.0f + bar_w + 2.0f + line : 0.0f);

  dl->AddText(p0, text, title.c_str());

  // Vertex room: the heat map takes what the dots (8 each, up to kMaxDots) and the lines leave.
  constexpr long kMaxDots = 4000, kLinesRoom = 12000;
  const long room = vertex_room(dl);
  const long dots_room = std::min<long>(kMaxDots, std::max<long>(0, (room - kLinesRoom) / 2 / 8));
  dl->PushClipRect(ImVec2(X0, Y0), ImVec2(X1, Y1), true);
  heat_map(dl, p, lc, cache.node_colors, room - kLinesRoom - dots_room * 8);

  // Beyond neo-Hookean's wall: hatched.
  const bool barrier = !model_allows_inversion(model);
  if (barrier && domain.s2_min < 0.0) {
    const float wy = p.y(0.0);
    for (float k = X0 - (Y1 - wy); k < X1; k += 8.0f)
      dl->AddLine(ImVec2(k, Y1), ImVec2(k + (Y1 - wy), wy), kHatch, 1.0f);
    const char* inf = "\u03a8 = +\u221e (det F \u2264 0)";
    const ImVec2 ts = ImGui::CalcTextSize(inf);
    if (Y1 - wy > ts.y + 6.0f && X1 - X0 > ts.x + 8.0f)
      dl->AddText(ImVec2(0.5f * (X0 + X1 - ts.x), 0.5f * (wy + Y1 - ts.y)),
                  IM_COL32(255, 255, 255, 255), inf);
  }
  // Contours.
  for (const ContourLine& c : lc.contours) {
    cache.scratch.resize(c.points.size());
    for (size_t k = 0; k < c.points.size(); ++k)
      cache.scratch[k] = ImVec2(p.x(c.points[k].s1), p.y(c.points[k].s2));
    dl->AddPolyline(cache.scratch.data(), static_cast<int>(cache.scratch.size()), kContour, 0,
                    1.0f);
  }
  // s1 s2 = 0: the wall (neo-Hookean), or the dashed det F = 0 the others cross.
  if (domain.s2_min < 0.0) {
    if (barrier)
      dl->AddLine(ImVec2(X0, p.y(0.0)), ImVec2(X1, p.y(0.0)), kInk, 3.0f);
    else
      dashed_line(dl, ImVec2(X0, p.y(0.0)), ImVec2(X1, p.y(0.0)), kInk, 1.5f);
  }
  if (barrier)
    dl->AddLine(ImVec2(X0 + 1.5f, Y0), ImVec2(X0 + 1.5f, p.y(std::max(0.0, domain.s2_min))), kInk,
                3.0f);
  dl->AddCircle(ImVec2(p.x(1.0), p.y(1.0)), 4.5f, kInk, 12, 1.6f);

  // The triangles: one dot per 3-pixel bin (more would cover each other), a white-edged
  // blue square each.
  const float bin = 3.0f;
  const int bw = static_cast<int>((X1 - X0) / bin) + 2, bh = static_cast<int>((Y1 - Y0) / bin) + 2;
  cache.occupied.assign(static_cast<size_t>(bw) * static_cast<size_t>(bh), 0);
  int drawn = 0;
  dl->PopClipRect();
  dl->PushClipRect(ImVec2(X0 - 3.0f, Y0 - 3.0f), ImVec2(X1 + 3.0f, Y1 + 3.0f), true);
  // A triangle beyond the domain (a stretch past 2) is pinned to its edge, pale.
  for (const SigmaPair& s : points) {
    if (drawn >= dots_room) break;
    const bool inside = s.s1 >= domain.s1_min && s.s1 <= domain.s1_max && s.s2 >= domain.s2_min &&
                        s.s2 <= domain.s2_max;
    const float x = p.x(std::clamp(s.s1, domain.s1_min, domain.s1_max));
    const float y = p.y(std::clamp(s.s2, domain.s2_min, domain.s2_max));
    const int bx = std::clamp(static_cast<int>((x - X0) / bin), 0, bw - 1);
    const int by = std::clamp(static_cast<int>((y - Y0) / bin), 0, bh - 1);
    std::uint8_t& o = cache.occupied[static_cast<size_t>(bx + bw * by)];
    if (o) continue;
    o = 1;
    dl->AddRectFilled(ImVec2(x - 2.5f, y - 2.5f), ImVec2(x + 2.5f, y + 2.5f),
                      inside ? kDotEdge : kDotFill);
    dl->AddRectFilled(ImVec2(x - 1.6f, y - 1.6f), ImVec2(x + 1.6f, y + 1.6f),
                      inside ? kDotFill : kDotPinned);
    ++drawn;
  }
  cache.dots_drawn = drawn;
  if (selected >= 0 && static_cast<size_t>(selected) < points.size()) {
    const SigmaPair s = points[static_cast<size_t>(selected)];
    const ImVec2 c(p.x(std::clamp(s.s1, domain.s1_min, domain.s1_max)),
                   p.y(std::clamp(s.s2, domain.s2_min, domain.s2_max)));
    dl->AddCircle(c, 7.0f, IM_COL32(255, 255, 255, 255), 16, 4.0f);
    dl->AddCircle(c, 7.0f, IM_COL32(0, 0, 0, 255), 16, 2.0f);
    dl->AddRectFilled(ImVec2(c.x - 2.5f, c.y - 2.5f), ImVec2(c.x + 2.5f, c.y + 2.5f), kDotFill);
  }
  dl->PopClipRect();
  dl->AddRect(ImVec2(X0, Y0), ImVec2(X1, Y1), text, 0.0f, 0, 1.0f);

  // Ticks every 0.5 when their labels (and the axis name between the last two) have room,
  // else every 1.
  const float name1_w = ImGui::CalcTextSize("\u03c3\u2081").x;
  const double step1 = p.ppu * 0.5f >= ImGui::CalcTextSize("1.5").x + name1_w + 12.0f ? 0.5 : 1.0;
  const double step2 = p.ppu * 0.5f >= 2.0f * line ? 0.5 : 1.0;
  char buf[32];
  for (double v = std::ceil(domain.s1_min / step1) * step1; v <= domain.s1_max + 1e-9; v += step1) {
    std::snprintf(buf, sizeof buf, "%g", v);
    const float w = ImGui::CalcTextSize(buf).x;
    dl->AddLine(ImVec2(p.x(v), Y1), ImVec2(p.x(v), Y1 + 3.0f), text);
    dl->AddText(ImVec2(p.x(v) - w / 2, Y1 + 3.0f), text, buf);
  }
  for (double v = std::ceil(domain.s2_min / step2) * step2; v <= domain.s2_max + 1e-9; v += step2) {
    std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-9 ? 0.0 : v);
    const std::string label = buf[0] == '-' ? "\u2212" + std::string(buf + 1) : std::string(buf);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    dl->AddLine(ImVec2(X0 - 3.0f, p.y(v)), ImVec2(X0, p.y(v)), text);
    dl->AddText(ImVec2(X0 - 5.0f - w, p.y(v) - line / 2), text, label.c_str());
  }
  // The axis names sit between the last two ticks of their axis.
  const double name_at1 = domain.s1_max - step1 / 2, name_at2 = domain.s2_max - step2 / 2;
  dl->AddText(ImVec2(p.x(name_at1) - name1_w / 2, Y1 + 3.0f), text, "\u03c3\u2081");
  dl->AddText(ImVec2(X0 - 5.0f - ImGui::CalcTextSize("\u03c3\u2082").x, p.y(name_at2) - line / 2),
              text, "\u03c3\u2082");

  // The colour bar: the map is piecewise linear in t, 8 pieces, each one gradient rectangle;
  // a tick at every contour level, the decades labelled (1k, 10k, ...: Pa, as the title says).
  const float bx0 = bar_below ? X0 : X1 + 8.0f, bx1 = bar_below ? X1 : bx0 + bar_w;
  const float by0 = bar_below ? Y1 + x_ticks + 6.0f : Y0, by1 = bar_below ? by0 + bar_w : Y1;
  // Position t on the bar: along x from the left (below), along y from the bottom (side).
  const auto at = [&](double t) {
    return bar_below ? bx0 + static_cast<float>(t) * (bx1 - bx0)
                     : by1 - static_cast<float>(t) * (by1 - by0);
  };
  for (int k = 0; k < 8; ++k) {
    const ImU32 c0 = to_u32(landscape_scale_color(k / 8.0)),
                c1 = to_u32(landscape_scale_color((k + 1) / 8.0));
    if (bar_below)
      dl->AddRectFilledMultiColor(ImVec2(at(k / 8.0), by0), ImVec2(at((k + 1) / 8.0) + 0.5f, by1),
                                  c0, c1, c1, c0);
    else
      dl->AddRectFilledMultiColor(ImVec2(bx0, at((k + 1) / 8.0)), ImVec2(bx1, at(k / 8.0) + 0.5f),
                                  c1, c1, c0, c0);
  }
  dl->AddRect(ImVec2(bx0, by0), ImVec2(bx1, by1), text);
  for (double level : lc.levels) {
    const float q = at(landscape_scale_position(lc.scale, level));
    if (bar_below)
      dl->AddLine(ImVec2(q, by0), ImVec2(q, by1 + 2.0f), kInk);
    else
      dl->AddLine(ImVec2(bx0, q), ImVec2(bx1 + 3.0f, q), kInk);
    const double decade = std::pow(10.0, std::floor(std::log10(level) + 1e-9));
    if (std::abs(level / decade - 1.0) > 1e-6) continue;  // 3 x 10^k: a tick only
    const char* suffix = decade >= 1e9 ? "G" : decade >= 1e6 ? "M" : decade >= 1e3 ? "k" : "";
    const double unit = decade >= 1e9 ? 1e9 : decade >= 1e6 ? 1e6 : decade >= 1e3 ? 1e3 : 1.0;
    std::snprintf(buf, sizeof buf, "%g%s", level / unit, suffix);
    const float w = ImGui::CalcTextSize(buf).x;
    if (bar_below)
      dl->AddText(ImVec2(std::clamp(q - w / 2, bx0 - 4.0f, bx1 + 4.0f - w), by1 + 2.0f), text, buf);
    else
      dl->AddText(ImVec2(bx1 + 5.0f, q - line / 2), text, buf);
  }

  // The panel as one item, and what is under the mouse.
  ImGui::PushID(&cache);  // one id per panel: two panels in one window do not collide
  ImGui::InvisibleButton("##landscape", ImVec2(size.x, std::min(size.y, used_h)));
  ImGui::PopID();
  if (ImGui::IsItemHovered()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    if (m.x >= X0 && m.x <= X1 && m.y >= Y0 && m.y <= Y1) {
      const double s1 = domain.s1_min + (m.x - X0) / p.ppu, s2 = domain.s2_max - (m.y - Y0) / p.ppu;
      const std::string psi = format_pascal(landscape_psi(model, lame, s1, s2));
      ImGui::SetTooltip("\u03c3\u2081 = %.3f   \u03c3\u2082 = %.3f\n\u03a8 = %s", s1, s2,
                        psi.c_str());
    }
  }
}

void draw_landscape_panel(const Simulation& sim, int selected, ImVec2 size,
                          LandscapePanelCache& cache) {
  triangle_sigmas(sim, &cache.sigma);
  draw_landscape_panel(sim.scene.model, sim.scene.lame, cache.sigma, selected, size, cache);
}

}  // namespace invfree
