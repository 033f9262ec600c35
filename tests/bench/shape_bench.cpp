// Meshing time of the shapes (core/shape/shape_mesh.h; issue 27: a 20,000-triangle shape
// meshed in <= 200 ms): a disk and a ring at max_edge giving about 20,000 triangles, and
// the validation of a 20,000-point outline. The meshing figures call triangulate_region
// (CGAL) on a ready region, plus the whole mesh_shape path with its cache defeated.
//   build/release/tests/shape/invfree_shape_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "shape/polygon_checks.h"
#include "shape/shape_mesh.h"
#include "shape/shape_region.h"
#include "shape/triangulate.h"

namespace invfree {
namespace {

ShapeDef disk() {
  ShapeDef s;
  s.kind = ShapeKind::Disk;
  s.radius = 0.5;
  return s;
}
ShapeDef ring() {
  ShapeDef s;
  s.kind = ShapeKind::Ring;
  s.radius = 0.5;
  s.inner_radius = 0.3;
  return s;
}

// max_edge for about 20,000 triangles by the documented estimate.
double max_edge_for(const ShapeDef& s, double triangles) {
  return std::sqrt(kTriangleEstimateFactor * shape_area(s) / (std::sqrt(3.0) / 4 * triangles));
}

void mesh_region(benchmark::State& state, ShapeDef s) {
  const double h = max_edge_for(s, 20000);
  const ShapeRegion region = shape_region(s, h);
  long triangles = 0;
  for (auto _ : state) {
    const Triangulation t = triangulate_region(region.loops, h, 100'000'000);
    triangles = static_cast<long>(t.triangles.size());
    benchmark::DoNotOptimize(t.nodes.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

void mesh_shape_uncached(benchmark::State& state, ShapeDef s) {
  const double h = max_edge_for(s, 20000);
  long triangles = 0;
  int k = 0;
  for (auto _ : state) {
    // A different max_edge in the last bits each time: the cache never hits.
    const ShapeMeshResult r = mesh_shape(s, h * (1 + 1e-12 * (++k % 1000)));
    triangles = r.mesh.triangle_count();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

void validate_outline(benchmark::State& state) {
  const int n = 20000;
  Loop wavy(n);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    const double r = 1 + 0.05 * std::sin(40 * t);
    wavy[k] = Vec2(r * std::cos(t), r * std::sin(t));
  }
  for (auto _ : state) benchmark::DoNotOptimize(check_loop(wavy, "outline"));
}

BENCHMARK_CAPTURE(mesh_region, disk, disk())->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mesh_region, ring, ring())->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mesh_shape_uncached, disk, disk())->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mesh_shape_uncached, ring, ring())->Unit(benchmark::kMillisecond);
BENCHMARK(validate_outline)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace invfree

BENCHMARK_MAIN();
