// Dear ImGui's draw data turned into pixels on the CPU, without GL: every draw command's
// triangles filled with their vertices' colours and the font atlas's alpha (nearest texel),
// blended over a background, inside the command's clip rectangle. Not the GPU's exact
// rasterisation rules, but deterministic: the landscape panel's golden and its picture for
// the docs come from it, so they need no display.
#pragma once

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "tests/render/image_compare.h"

namespace invfree::test {

inline RgbImage draw_data_image(const ImDrawData* dd, int width, int height,
                                ImU32 background = IM_COL32(240, 240, 240, 255)) {
  unsigned char* atlas = nullptr;
  int aw = 0, ah = 0;
  ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&atlas, &aw, &ah);
  std::vector<float> px(static_cast<size_t>(width) * height * 3);
  for (size_t k = 0; k < px.size(); k += 3) {
    px[k] = (background & 0xff) / 255.0f;
    px[k + 1] = ((background >> 8) & 0xff) / 255.0f;
    px[k + 2] = ((background >> 16) & 0xff) / 255.0f;
  }
  for (int l = 0; l < dd->CmdListsCount; ++l) {
    const ImDrawList* list = dd->CmdLists[l];
    for (const ImDrawCmd& cmd : list->CmdBuffer) {
      if (cmd.UserCallback) continue;
      const int cx0 = std::max(0, static_cast<int>(std::floor(cmd.ClipRect.x)));
      const int cy0 = std::max(0, static_cast<int>(std::floor(cmd.ClipRect.y)));
      const int cx1 = std::min(width, static_cast<int>(std::ceil(cmd.ClipRect.z)));
      const int cy1 = std::min(height, static_cast<int>(std::ceil(cmd.ClipRect.w)));
      for (unsigned e = 0; e + 2 < cmd.ElemCount; e += 3) {
        const ImDrawVert* v[3];
        for (int k = 0; k < 3; ++k)
          v[k] = &list->VtxBuffer[static_cast<int>(
              cmd.VtxOffset + list->IdxBuffer[static_cast<int>(cmd.IdxOffset + e + k)])];
        const float area = (v[1]->pos.x - v[0]->pos.x) * (v[2]->pos.y - v[0]->pos.y) -
                           (v[2]->pos.x - v[0]->pos.x) * (v[1]->pos.y - v[0]->pos.y);
        if (std::abs(area) < 1e-12f) continue;
        const int x0 = std::max(
            cx0, static_cast<int>(std::floor(std::min({v[0]->pos.x, v[1]->pos.x, v[2]->pos.x}))));
        const int x1 = std::min(
            cx1, static_cast<int>(std::ceil(std::max({v[0]->pos.x, v[1]->pos.x, v[2]->pos.x}))));
        const int y0 = std::max(
            cy0, static_cast<int>(std::floor(std::min({v[0]->pos.y, v[1]->pos.y, v[2]->pos.y}))));
        const int y1 = std::min(
            cy1, static_cast<int>(std::ceil(std::max({v[0]->pos.y, v[1]->pos.y, v[2]->pos.y}))));
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) {
            const float sx = x + 0.5f, sy = y + 0.5f;
            float w[3];
            for (int k = 0; k < 3; ++k) {
              const ImDrawVert* a = v[(k + 1) % 3];
              const ImDrawVert* b = v[(k + 2) % 3];
              w[k] = ((b->pos.x - a->pos.x) * (sy - a->pos.y) -
                      (sx - a->pos.x) * (b->pos.y - a->pos.y)) /
                     area;
            }
            // Inside or on an edge (a pixel on an edge two triangles share is blended twice).
            if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
            float c[4] = {0, 0, 0, 0}, u = 0, t = 0;
            for (int k = 0; k < 3; ++k) {
              const ImU32 col = v[k]->col;
              for (int ch = 0; ch < 4; ++ch) c[ch] += w[k] * ((col >> (8 * ch)) & 0xff) / 255.0f;
              u += w[k] * v[k]->uv.x;
              t += w[k] * v[k]->uv.y;
            }
            const int tx = std::clamp(static_cast<int>(u * aw), 0, aw - 1);
            const int ty = std::clamp(static_cast<int>(t * ah), 0, ah - 1);
            const float alpha = c[3] * atlas[(static_cast<size_t>(ty) * aw + tx) * 4 + 3] / 255.0f;
            float* d = &px[(static_cast<size_t>(y) * width + x) * 3];
            for (int ch = 0; ch < 3; ++ch) d[ch] = c[ch] * alpha + d[ch] * (1.0f - alpha);
          }
      }
    }
  }
  RgbImage image;
  image.width = width;
  image.height = height;
  image.rgb.resize(px.size());
  for (size_t k = 0; k < px.size(); ++k)
    image.rgb[k] = static_cast<std::uint8_t>(std::lround(std::clamp(px[k], 0.0f, 1.0f) * 255.0f));
  return image;
}

}  // namespace invfree::test
