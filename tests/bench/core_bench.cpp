// Google Benchmark figures for the core: per-triangle kernels (ns per triangle for the
// value, gradient and projected Hessian of each model) and whole `compress` steps at
// several resolutions (the mesh is run to the compression phase first, so the step
// measured has active contacts).
//   build/release/tests/bench/invfree_bench --benchmark_filter=Step
#include <benchmark/benchmark.h>

#include <random>

#include "core/models.h"
#include "core/scene.h"
#include "core/simulation.h"
#include "core/triangle_elasticity.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

std::vector<Mat2> random_fs(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> a(-3, 3), s(0.5, 1.5);
  std::vector<Mat2> out;
  for (int k = 0; k < n; ++k) out.push_back(rotation(a(rng)) * Vec2(s(rng), s(rng)).asDiagonal() * rotation(a(rng)));
  return out;
}

template <class M>
void BM_Value(benchmark::State& state) {
  const auto fs = random_fs(1024);
  for (auto _ : state)
    for (const Mat2& F : fs) benchmark::DoNotOptimize(M::energy_density(F, kLame));
  state.SetItemsProcessed(state.iterations() * fs.size());
}

template <class M>
void BM_Gradient(benchmark::State& state) {
  const auto fs = random_fs(1024);
  const Mat46 dFdx = deformation_gradient_jacobian(Mat2::Identity() * 4.0);
  for (auto _ : state)
    for (const Mat2& F : fs) benchmark::DoNotOptimize(TriangleElasticity<M>::gradient(F, dFdx, 0.03, kLame));
  state.SetItemsProcessed(state.iterations() * fs.size());
}

template <class M>
void BM_ProjectedHessian(benchmark::State& state) {
  const auto fs = random_fs(1024);
  const Mat46 dFdx = deformation_gradient_jacobian(Mat2::Identity() * 4.0);
  const auto proj = static_cast<HessianProjection>(state.range(0));
  for (auto _ : state)
    for (const Mat2& F : fs) benchmark::DoNotOptimize(TriangleElasticity<M>::hessian(F, dFdx, 0.03, kLame, proj));
  state.SetItemsProcessed(state.iterations() * fs.size());
}

BENCHMARK(BM_Value<NeoHookean>);
BENCHMARK(BM_Value<StableNeoHookean>);
BENCHMARK(BM_Value<Arap>);
BENCHMARK(BM_Value<LinearElasticity>);
BENCHMARK(BM_Gradient<NeoHookean>);
BENCHMARK(BM_Gradient<StableNeoHookean>);
BENCHMARK(BM_Gradient<Arap>);
BENCHMARK(BM_Gradient<LinearElasticity>);
BENCHMARK(BM_ProjectedHessian<NeoHookean>)->Arg(0)->Arg(1)->ArgName("projection");
BENCHMARK(BM_ProjectedHessian<StableNeoHookean>)->Arg(0)->Arg(1)->ArgName("projection");
BENCHMARK(BM_ProjectedHessian<Arap>)->Arg(0)->ArgName("projection");
BENCHMARK(BM_ProjectedHessian<LinearElasticity>)->Arg(0)->ArgName("projection");

// One step of `compress` at n_seg = range(0), measured over the whole run of the demo
// (fall, contact, compression, rest): the mean per step, like the reference timing.
void BM_CompressStep(benchmark::State& state) {
  SceneDef scene = *find_builtin_scene("compress");
  scene.n_seg = static_cast<int>(state.range(0));
  Simulation sim = make_simulation(scene);
  long iterations = 0, steps = 0;
  for (auto _ : state) {
    if (sim.step_count >= 300) {
      state.PauseTiming();
      sim = make_simulation(scene);
      state.ResumeTiming();
    }
    const StepReport r = step(sim);
    if (r.status != StepStatus::Ok) {
      state.SkipWithError(r.message.c_str());
      break;
    }
    iterations += r.newton_iterations;
    ++steps;
  }
  state.counters["newton_per_step"] = steps ? double(iterations) / steps : 0.0;
}
BENCHMARK(BM_CompressStep)->Arg(4)->Arg(8)->Arg(16)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace invfree

BENCHMARK_MAIN();
