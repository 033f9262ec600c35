// The live/web landscape panel (app/live/landscape_panel.h) drawn into a headless Dear ImGui
// frame (no window, no GL: the draw lists are read back): it draws, keeps its grid between
// frames, rebuilds it when the model or the Lame parameters change, puts a dot per occupied
// spot, and stays within the 65536 vertices a draw list has on the web page (16-bit indices
// without the backend's vertex offsets) however many triangles there are; and a golden of
// it, rasterised on the CPU (draw_data_image.h) with the live window's font and glyphs.
#include "app/live/landscape_panel.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <random>
#include <string>

#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "tests/landscape/draw_data_image.h"
#include "tests/test_paths.h"
#include "triangle_fields.h"

extern "C" const unsigned char invfree_chart_font_begin[];  // app/plot/font.cpp
extern "C" const unsigned char invfree_chart_font_end[];

namespace invfree {
namespace {

class Frame {
 public:
  Frame() {
    ctx_ = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(800, 900);
    io.DeltaTime = 1.0f / 60.0f;
    io.IniFilename = nullptr;
    // The live window's font (DejaVu Sans at 16 px) with the Greek and symbols it adds.
    ImFontGlyphRangesBuilder builder;
    builder.AddRanges(io.Fonts->GetGlyphRangesDefault());
    builder.AddText(
        "\u03bc\u03bb\u03bd\u03c3\u03c8\u03a8\u0394\u2264\u2265\u00b7\u00d7\u2212\u00b2\u2202\u221e"
        "\u2192\u2081\u2082");
    builder.BuildRanges(&ranges_);
    ImFontConfig cfg;
    cfg.FontDataOwnedByAtlas = false;
    io.Fonts->AddFontFromMemoryTTF(
        const_cast<unsigned char*>(invfree_chart_font_begin),
        static_cast<int>(invfree_chart_font_end - invfree_chart_font_begin), 16.0f, &cfg,
        ranges_.Data);
    unsigned char* pixels;
    int w, h;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    ImGui::StyleColorsDark();  // as the live window
  }
  ~Frame() { ImGui::DestroyContext(ctx_); }
  // One frame with the panel in a window; returns the window's vertex count.
  template <class Draw>
  int run(Draw draw) {
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(500, 800));
    ImGui::Begin("panel");
    draw();
    ImGui::End();
    ImGui::Render();
    const ImDrawData* d = ImGui::GetDrawData();
    return d->TotalVtxCount;
  }

 private:
  ImGuiContext* ctx_;
  ImVector<ImWchar> ranges_;
};

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

TEST(LandscapePanel, DrawsAndKeepsItsGridBetweenFrames) {
  Frame f;
  LandscapePanelCache cache;
  std::vector<SigmaPair> pts = {{1.0, 1.0}, {1.1, 0.9}, {1.5, 0.4}};
  for (int k = 0; k < 3; ++k) {
    const int v = f.run(
        [&] { draw_landscape_panel(Model::NeoHookean, kLame, pts, 1, ImVec2(400, 500), cache); });
    EXPECT_GT(v, 1000);
    EXPECT_LT(v, 65536);
    pts[2].s2 += 0.1;  // the dots move; the grid stays
  }
  EXPECT_EQ(cache.landscape.rebuilds, 1);
  EXPECT_EQ(cache.dots_drawn, 3);
  EXPECT_EQ(cache.node_colors.size(), cache.landscape.grid.psi.size());
  // Another model, other Lame parameters: rebuilt once each.
  f.run([&] { draw_landscape_panel(Model::Arap, kLame, pts, -1, ImVec2(400, 500), cache); });
  Lame soft = kLame;
  soft.mu *= 0.5;
  f.run([&] { draw_landscape_panel(Model::Arap, soft, pts, -1, ImVec2(400, 500), cache); });
  f.run([&] { draw_landscape_panel(Model::Arap, soft, pts, -1, ImVec2(400, 500), cache); });
  EXPECT_EQ(cache.landscape.rebuilds, 3);
  EXPECT_EQ(cache.landscape.grid.domain, landscape_domain(Model::Arap));
}

TEST(LandscapePanel, ManyTrianglesStayWithinOneDrawListsVertices) {
  Frame f;
  LandscapePanelCache cache;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 2.0), v(-2.0, 2.0);
  std::vector<SigmaPair> pts(200000);
  for (auto& p : pts) p = {u(rng), v(rng)};
  const int vertices = f.run([&] {
    draw_landscape_panel(Model::StableNeoHookean, kLame, pts, 5, ImVec2(480, 760), cache);
  });
  EXPECT_LT(vertices, 65536);
  EXPECT_GT(cache.dots_drawn, 1000);
}

TEST(LandscapePanel, DrawsASimulationsTriangles) {
  Frame f;
  LandscapePanelCache cache;
  SceneDef s = *load_builtin_scene("compress").scene;
  ASSERT_EQ(apply_override(s, "mesh.n_seg=8"), "");
  Simulation sim = make_simulation(s);
  f.run([&] { draw_landscape_panel(sim, 0, ImVec2(300, 360), cache); });
  EXPECT_EQ(static_cast<int>(cache.sigma.size()), sim.mesh.triangle_count());
  EXPECT_GE(cache.dots_drawn, 1);
  EXPECT_EQ(cache.landscape.grid.model, sim.scene.model);
  EXPECT_EQ(cache.landscape.grid.lame, sim.scene.lame);
}

SceneDef scene(const std::string& name, const std::vector<std::string>& overrides) {
  SceneDef s = *load_builtin_scene(name).scene;
  for (const auto& o : overrides) EXPECT_EQ(apply_override(s, o), "") << o;
  return s;
}

std::string golden_dir() {
  return std::string(test::source_dir()) + "/tests/landscape/goldens";
}

// The panel at the live window's size (its landscape window is 270 px wide at UI scale 1:
// 254 inside, asked for 1.2 times as tall), pixels compared with
// goldens/landscape_panel_*.png (INVFREE_UPDATE_GOLDENS=1 rewrites them: look first).
void expect_panel_golden(const Simulation& sim, int selected, const std::string& name) {
  Frame f;
  LandscapePanelCache cache;
  ImGui::GetIO().DisplaySize = ImVec2(270, 360);
  f.run([&] { draw_landscape_panel(sim, selected, ImVec2(254, 305), cache); });
  const test::RgbImage image = test::draw_data_image(ImGui::GetDrawData(), 270, 360);
  const std::string m = test::check_golden(image, name, golden_dir(), test::golden_failure_dir());
  EXPECT_TRUE(m.empty()) << m;
}

TEST(LandscapePanel, NeoHookeanSquashedGolden) {
  // compress at n_seg 8 squashed to the ceiling's stop: the dots spread along the wall's
  // side of the bowl, none beyond it.
  Simulation sim = make_simulation(scene("compress", {"mesh.n_seg=8"}));
  while (sim.step_count < 280) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  std::vector<SigmaPair> s;
  triangle_sigmas(sim, &s);
  int lowest = 0;
  for (size_t t = 0; t < s.size(); ++t)
    if (s[t].s2 < s[static_cast<size_t>(lowest)].s2) lowest = static_cast<int>(t);
  EXPECT_GT(s[static_cast<size_t>(lowest)].s2, 0.0);
  expect_panel_golden(sim, lowest, "landscape_panel_neo_hookean");
}

TEST(LandscapePanel, LinearInvertedGolden) {
  // The soft linear square thrown at the ground (as the render golden linear_inverted): dots
  // below s2 = 0, the selected one of them ringed.
  Simulation sim = make_simulation(scene("compress", {"material.model=linear", "material.E=1e4",
                                                      "mesh.n_seg=8", "initial.velocity=[0,-8]"}));
  while (sim.step_count < 23) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  std::vector<SigmaPair> s;
  triangle_sigmas(sim, &s);
  int lowest = 0;
  for (size_t t = 0; t < s.size(); ++t)
    if (s[t].s2 < s[static_cast<size_t>(lowest)].s2) lowest = static_cast<int>(t);
  EXPECT_LT(s[static_cast<size_t>(lowest)].s2, 0.0);
  expect_panel_golden(sim, lowest, "landscape_panel_linear");
}

}  // namespace
}  // namespace invfree
