// Google Benchmark figures for the energy landscape panel (issue 26: a landscape redraw
// <= 2 ms), in a headless Dear ImGui frame (no window, no GL: what the panel costs on the
// CPU, the draw lists it fills; the GPU's share is drawing ~40k vertices):
//   Frame/empty            a frame with an empty window (subtract it)
//   Frame/cached           + the panel, grid cached: n_seg 64's 8,192 triangles' (s1, s2)
//                          and the dots, the heat-map mesh, the contours (every frame)
//   Frame/rebuild          + the panel with the cache invalidated (model or Lame changed):
//                          the grid, its contours and colours rebuilt first
//   TriangleSigmas         the 8,192 polar SVDs alone
//   GridRebuild/<model>    update_landscape_cache on a miss, per model
// The mesh is compress at n_seg 64 with every node jittered, so the triangles spread over the
// landscape as a deformed body's do (at rest they would all be one dot).
//   build/h3/tests/bench/invfree_landscape_bench
#include <benchmark/benchmark.h>
#include <imgui.h>

#include <random>

#include "app/live/landscape_panel.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace invfree {
namespace {

Simulation jittered_compress() {
  SceneDef s = *load_builtin_scene("compress").scene;
  apply_override(s, "mesh.n_seg=64");
  Simulation sim = make_simulation(s);
  std::mt19937 rng(3);
  const double edge = body_edge_length(sim.scene, 0);
  std::uniform_real_distribution<double> d(-0.25 * edge, 0.25 * edge);
  for (Eigen::Index k = 0; k < sim.x.size(); ++k) sim.x[k] += d(rng);
  return sim;
}

struct ImGuiFrame {
  ImGuiFrame() {
    ctx = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(1280, 900);
    io.DeltaTime = 1.0f / 60.0f;
    io.IniFilename = nullptr;
    unsigned char* pixels;
    int w, h;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  ~ImGuiFrame() { ImGui::DestroyContext(ctx); }
  template <class Draw>
  void run(Draw draw) {
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(420, 620));
    ImGui::Begin("panel");
    draw();
    ImGui::End();
    ImGui::Render();
  }
  ImGuiContext* ctx;
};

const ImVec2 kPanel(400, 560);

void BM_FrameEmpty(benchmark::State& state) {
  ImGuiFrame f;
  for (auto _ : state) f.run([] {});
}
BENCHMARK(BM_FrameEmpty)->Name("Frame/empty")->Unit(benchmark::kMicrosecond);

void BM_FrameCached(benchmark::State& state) {
  const Simulation sim = jittered_compress();
  ImGuiFrame f;
  LandscapePanelCache cache;
  int vertices = 0;
  for (auto _ : state) {
    f.run([&] { draw_landscape_panel(sim, 100, kPanel, cache); });
    vertices = ImGui::GetDrawData()->TotalVtxCount;
  }
  state.counters["triangles"] = sim.mesh.triangle_count();
  state.counters["dots"] = cache.dots_drawn;
  state.counters["vertices"] = vertices;
  state.counters["rebuilds"] = cache.landscape.rebuilds;
}
BENCHMARK(BM_FrameCached)->Name("Frame/cached")->Unit(benchmark::kMicrosecond);

void BM_FrameRebuild(benchmark::State& state) {
  const Simulation sim = jittered_compress();
  ImGuiFrame f;
  LandscapePanelCache cache;
  for (auto _ : state) {
    cache.landscape.valid = false;
    f.run([&] { draw_landscape_panel(sim, 100, kPanel, cache); });
  }
  state.counters["grid_nodes"] = static_cast<double>(cache.landscape.grid.psi.size());
}
BENCHMARK(BM_FrameRebuild)->Name("Frame/rebuild")->Unit(benchmark::kMicrosecond);

void BM_TriangleSigmas(benchmark::State& state) {
  const Simulation sim = jittered_compress();
  std::vector<SigmaPair> s;
  for (auto _ : state) {
    triangle_sigmas(sim, &s);
    benchmark::DoNotOptimize(s.data());
  }
  state.SetItemsProcessed(state.iterations() * sim.mesh.triangle_count());
}
BENCHMARK(BM_TriangleSigmas)->Name("TriangleSigmas")->Unit(benchmark::kMicrosecond);

void BM_GridRebuild(benchmark::State& state) {
  const Model m = static_cast<Model>(state.range(0));
  const Lame lame = lame_from_young_poisson(1e5, 0.4);
  LandscapeCache cache;
  for (auto _ : state) {
    cache.valid = false;
    update_landscape_cache(m, lame, landscape_domain(m), kLandscapePanelPerUnit, &cache);
    benchmark::DoNotOptimize(cache.contours.data());
  }
  state.SetLabel(model_name(m));
  state.counters["contour_lines"] = static_cast<double>(cache.contours.size());
}
BENCHMARK(BM_GridRebuild)->Name("GridRebuild")->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace invfree

BENCHMARK_MAIN();
