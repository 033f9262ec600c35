// What a colouring costs a live frame (issue 26: at most 5% of a frame at n_seg 64): for
// `compress` at n_seg 64 in its compression phase (run to step 120 outside the timing),
//  - Capture/<field>: capture_frame_state, which computes the field per triangle;
//  - Build/<field>: build_frame_vertices at 1280x720 (fills, edges, panel, legend);
//  - Frame/<field>: both plus the GL draw and read-back offscreen (OSMesa's llvmpipe);
//  - Step: one simulation step, the other part of a live frame;
// with <field> det-f (today's frame), psi, stress, clamped, and stress+glyphs. A
// colouring's added cost is its time minus det-f's. Run by hand (not a test):
//   build/release/tests/bench/invfree_frame_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/render/camera.h"
#include "app/render/frame_vertices.h"
#include "app/render/offscreen_context.h"
#include "app/render/renderer.h"
#include "app/render/text_atlas.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree {
namespace {

constexpr int kNSeg = 64, kWidth = 1280, kHeight = 720;

// compress at n_seg 64 stepped into the compression phase (step 120).
Simulation make_compressed() {
  SceneDef scene = *load_builtin_scene("compress").scene;
  scene.n_seg = kNSeg;
  Simulation s = make_simulation(scene);
  for (int k = 0; k < 120; ++k) step(s);
  return s;
}
// The same, made once for the drawing benchmarks.
const Simulation& compressed() {
  static const Simulation sim = make_compressed();
  return sim;
}

// range(0): a TriangleField, or 4 for stress with glyphs.
render::CaptureOptions capture_of(const benchmark::State& state) {
  render::CaptureOptions c;
  const int k = static_cast<int>(state.range(0));
  c.color_by = static_cast<TriangleField>(k == 4 ? 2 : k);
  c.stress_glyphs = k == 4;
  return c;
}
void label(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  state.SetLabel(k == 4 ? "stress+glyphs"
                        : enum_name(kTriangleFieldNames, static_cast<TriangleField>(k)));
}

void BM_Capture(benchmark::State& state) {
  const Simulation& sim = compressed();
  const render::CaptureOptions capture = capture_of(state);
  for (auto _ : state) benchmark::DoNotOptimize(render::capture_frame_state(sim, nullptr, capture));
  label(state);
}

void BM_Build(benchmark::State& state) {
  const Simulation& sim = compressed();
  const render::CaptureOptions capture = capture_of(state);
  const render::FrameState frame = render::capture_frame_state(sim, nullptr, capture);
  const render::FrameLayout L = render::frame_layout(kWidth, kHeight);
  const render::Camera cam = render::scene_camera(frame.scene, L);
  render::TextAtlas atlas;
  render::FrameVertices v;
  v.font_sizes = {31.0, 21.0, 18.0};  // the renderer's at 1280x720
  atlas.build(v.font_sizes);
  v.atlas = &atlas;
  render::DrawOptions options;
  options.stress_glyphs = capture.stress_glyphs;
  options.edges = false;  // as render and live leave them at n_seg 64 (too dense)
  for (auto _ : state) benchmark::DoNotOptimize(build_frame_vertices(v, frame, L, cam, options));
  label(state);
}

void BM_Frame(benchmark::State& state) {
  static std::unique_ptr<render::OffscreenContext> context;
  static std::unique_ptr<render::Renderer> renderer;
  std::string error;
  if (!context) context = render::OffscreenContext::create(&error);
  if (context && !renderer)
    renderer = render::Renderer::create(context->get_proc_address(), kWidth, kHeight, &error);
  if (!renderer) {
    state.SkipWithError(("no offscreen GL: " + error).c_str());
    return;
  }
  const Simulation& sim = compressed();
  const render::CaptureOptions capture = capture_of(state);
  render::DrawOptions options;
  options.stress_glyphs = capture.stress_glyphs;
  options.edges = false;
  std::vector<std::uint8_t> pixels;
  for (auto _ : state) {
    renderer->draw(render::capture_frame_state(sim, nullptr, capture), options);
    renderer->read_pixels(&pixels);  // waits for the drawing
  }
  label(state);
}

void BM_Step(benchmark::State& state) {
  Simulation sim = make_compressed();
  for (auto _ : state) {
    if (sim.step_count >= 260) {
      state.PauseTiming();
      sim = make_compressed();
      state.ResumeTiming();
    }
    if (step(sim).status != StepStatus::Ok) {
      state.SkipWithError("step failed");
      break;
    }
  }
}

BENCHMARK(BM_Capture)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Build)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Frame)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Step)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace invfree

BENCHMARK_MAIN();
