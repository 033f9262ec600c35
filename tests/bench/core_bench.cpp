// Google Benchmark figures for the core: per-triangle kernels (ns per triangle for the
// value, gradient and projected Hessian of each model, and the assembly's fused
// gradient + Hessian), one whole assembly and one energy evaluation of a compressed
// mesh (2 threads), and `compress` steps in the compression phase at several
// resolutions (the mesh is first run to step 120 outside the timing, so the steps
// measured have the ceiling pushing and contacts active); self-contact's broad phase and
// per-iteration pair work on two stacked squares.
//   build/release/tests/bench/invfree_bench --benchmark_filter=Step
// The whole-run scaling curve (every phase of the scene, medians) is `invfree bench`.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <random>

#include "collision/broad_phase.h"
#include "linalg/cholmod_backend.h"
#include "linalg/ldlt_backend.h"
#include "linalg/parallel.h"
#include "linalg/sparse_ldlt.h"
#include "material/models.h"
#include "material/triangle_elasticity.h"
#include "potential/incremental_potential.h"
#include "potential/self_contact_barrier.h"
#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/ccd.h"
#include "tests/scene/body_fixtures.h"
#include "solver/step_workspace.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

std::vector<Mat2> random_fs(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> a(-3, 3), s(0.5, 1.5);
  std::vector<Mat2> out;
  for (int k = 0; k < n; ++k)
    out.push_back(rotation(a(rng)) * Vec2(s(rng), s(rng)).asDiagonal() * rotation(a(rng)));
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
    for (const Mat2& F : fs)
      benchmark::DoNotOptimize(TriangleElasticity<M>::gradient(F, dFdx, 0.03, kLame));
  state.SetItemsProcessed(state.iterations() * fs.size());
}

template <class M>
void BM_ProjectedHessian(benchmark::State& state) {
  const auto fs = random_fs(1024);
  const Mat46 dFdx = deformation_gradient_jacobian(Mat2::Identity() * 4.0);
  const auto proj = static_cast<HessianProjection>(state.range(0));
  for (auto _ : state)
    for (const Mat2& F : fs)
      benchmark::DoNotOptimize(TriangleElasticity<M>::hessian(F, dFdx, 0.03, kLame, proj));
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

template <class M>
void BM_FusedGradientHessian(benchmark::State& state) {
  const auto fs = random_fs(1024);
  const Mat2 IB = Mat2::Identity() * 4.0;
  Vec6 g;
  Mat6 H;
  for (auto _ : state)
    for (const Mat2& F : fs) {
      TriangleElasticity<M>::gradient_hessian(F, IB, 0.03, kLame, HessianProjection::Diagonal, g,
                                              H);
      benchmark::DoNotOptimize(H);
    }
  state.SetItemsProcessed(state.iterations() * fs.size());
}
BENCHMARK(BM_FusedGradientHessian<NeoHookean>);
BENCHMARK(BM_FusedGradientHessian<StableNeoHookean>);

// A `compress` simulation at n_seg = n run into its compression phase (step 120).
Simulation compressed(int n_seg) {
  SceneDef scene = *load_builtin_scene("compress").scene;
  scene.n_seg = n_seg;
  Simulation sim = make_simulation(scene);
  for (int k = 0; k < 120; ++k) step(sim);
  return sim;
}

VecX state_of(const Simulation& sim) {
  VecX z(sim.workspace->problem.dof_count());
  z.head(sim.x.size()) = sim.x;
  z[sim.x.size()] = sim.ceiling_y;
  return z;
}

// One gradient + projected Hessian assembly (items: triangles).
void BM_Assembly(benchmark::State& state) {
  Simulation sim = compressed(static_cast<int>(state.range(0)));
  const VecX z = state_of(sim);
  VecX g;
  for (auto _ : state)
    ip_gradient_hessian(sim.workspace->problem, sim.workspace->caches, z, g, sim.workspace->newton.hessian);
  state.SetItemsProcessed(state.iterations() * sim.mesh.triangle_count());
  state.counters["threads"] = thread_count();
}
BENCHMARK(BM_Assembly)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

// One incremental-potential evaluation, as in the line search (items: triangles).
void BM_Energy(benchmark::State& state) {
  Simulation sim = compressed(static_cast<int>(state.range(0)));
  const VecX z = state_of(sim);
  for (auto _ : state) benchmark::DoNotOptimize(ip_energy(sim.workspace->problem, sim.workspace->caches, z));
  state.SetItemsProcessed(state.iterations() * sim.mesh.triangle_count());
}
BENCHMARK(BM_Energy)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

// compress's Hessian at n_seg after its first step (the pattern and values the solver
// factorises).
Eigen::SparseMatrix<double> compress_hessian(int n_seg) {
  SceneDef scene = *load_builtin_scene("compress").scene;
  scene.n_seg = n_seg;
  Simulation sim = make_simulation(scene);
  step(sim);
  VecX g;
  ip_gradient_hessian(sim.workspace->problem, sim.workspace->caches, state_of(sim), g,
                      sim.workspace->newton.hessian);
  return sim.workspace->newton.hessian.matrix;
}

// One forward + backward solve with the LDL^T factor of the projected Hessian after one
// step (the solver's ordering and split): the kernel PCG repeats once per iteration. A
// solve's work and memory traffic depend on the pattern alone, not on the values, so
// the first step's Hessian times it as well as a compressed one and takes a second
// instead of the 120 steps that `compressed` needs (about 40 s at n_seg 256:
// `invfree bench --sizes 256 --steps 120`).
// float:1 reads L rounded to float, as PCG does from kFloatPreconditionerMinEntries (pcg.h).
// Items: entries of L.
void BM_LdltSolve(benchmark::State& state) {
  const Eigen::SparseMatrix<double> h = compress_hessian(static_cast<int>(state.range(0)));
  SparseLdlt ldlt;
  analyze_like_the_solver(h, ldlt);  // METIS from 5,000 unknowns, as in the solver
  if (!ldlt.factorize(h)) {
    state.SkipWithError("factorisation failed");
    return;
  }
  const bool use_float = state.range(1) != 0;
  if (use_float) {
    ldlt.keep_float_copy(true);
    if (!ldlt.factorize(h)) {  // the copy is made by a factorisation
      state.SkipWithError("factorisation failed");
      return;
    }
  }
  const VecX b = VecX::Ones(h.rows());
  VecX x(h.rows());
  for (auto _ : state) use_float ? ldlt.solve_float(b, x) : ldlt.solve(b, x);
  state.SetItemsProcessed(state.iterations() * ldlt.factor_nonzeros());
  state.counters["L_nonzeros"] = static_cast<double>(ldlt.factor_nonzeros());
  const SparseLdlt::TreeParallelism tree = ldlt.tree_parallelism();
  state.counters["factor_work/span"] = tree.factor_work / tree.factor_span;
  state.counters["solve_work/span"] = tree.solve_work / tree.solve_span;
  state.counters["tasks"] = ldlt.task_count();
  state.counters["levels"] = ldlt.level_count();
  state.counters["schedule_x2"] = ldlt.schedule_speedup(2);
  state.counters["schedule_x16"] = ldlt.schedule_speedup(16);
}
BENCHMARK(BM_LdltSolve)
    ->ArgsProduct({{64, 128, 256}, {0, 1}})
    ->ArgNames({"n_seg", "float"})
    ->Unit(benchmark::kMillisecond);

// One numeric factorisation of the same Hessian (PCG renews its factor about once in ten
// steps; the direct solvers once per Newton iteration).
void BM_LdltFactorize(benchmark::State& state) {
  const Eigen::SparseMatrix<double> h = compress_hessian(static_cast<int>(state.range(0)));
  SparseLdlt ldlt;
  analyze_like_the_solver(h, ldlt);
  for (auto _ : state)
    if (!ldlt.factorize(h)) {
      state.SkipWithError("factorisation failed");
      return;
    }
  state.counters["L_nonzeros"] = static_cast<double>(ldlt.factor_nonzeros());
  // The flop model PCG's refresh rule reads (factor_flops), per second of a factorisation.
  state.counters["factor_flops"] = ldlt.factor_flops();
  state.counters["model_flop_rate"] =
      benchmark::Counter(ldlt.factor_flops() * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LdltFactorize)->Arg(64)->Arg(128)->Arg(256)->ArgName("n_seg")->Unit(benchmark::kMillisecond);

// CHOLMOD's supernodal factorisation of the same Hessian (the `cholmod` solver).
void BM_CholmodFactorize(benchmark::State& state) {
  const Eigen::SparseMatrix<double> h = compress_hessian(static_cast<int>(state.range(0)));
  CholmodBackend chol;
  if (!chol.analyze(h)) {
    state.SkipWithError("no CHOLMOD");
    return;
  }
  for (auto _ : state)
    if (!chol.factorize(h)) {
      state.SkipWithError("factorisation failed");
      return;
    }
}
BENCHMARK(BM_CholmodFactorize)->Arg(64)->Arg(128)->Arg(256)->ArgName("n_seg")->Unit(benchmark::kMillisecond);

// Steps of `compress` at n_seg = range(0) in the compression phase (steps 120-260): the
// hardest part of the run. The whole-run medians come from `invfree bench`.
void BM_CompressStep(benchmark::State& state) {
  const int n_seg = static_cast<int>(state.range(0));
  Simulation sim = compressed(n_seg);
  long iterations = 0, steps = 0;
  for (auto _ : state) {
    if (sim.step_count >= 260) {
      state.PauseTiming();
      sim = compressed(n_seg);
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
BENCHMARK(BM_CompressStep)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Arg(64)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);

// Self-contact on two unit squares stacked 5 mm apart (n_seg each: 4 n_seg boundary edges
// per body, about n_seg pairs within dhat), every node moved by a random step of up to
// 2 mm: the broad phase over the step (dhat 1 cm), then what the pairs cost a Newton
// iteration: the barrier's value, its gradient and projected Hessians, and the CCD bound.
// Items: boundary edges.
struct StackedSquares {
  test::TwoSquares two;
  VecX x, p;
  explicit StackedSquares(int n_seg) : two(test::two_squares(1.0, n_seg, Vec2(0.1, -1.005))) {
    x = test::flat_positions(two.mesh.rest);
    p.resize(x.size());
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    for (int i = 0; i < p.size(); ++i) p[i] = u(rng);
  }
};

void BM_SelfContactBroadPhase(benchmark::State& state) {
  const StackedSquares s(static_cast<int>(state.range(0)));
  BroadPhaseGrid grid;
  std::vector<PointEdgePair> pairs;
  for (auto _ : state)
    swept_point_edge_candidates(s.two.boundary, s.x, s.p, 1.0, 0.01, grid, pairs);
  state.SetItemsProcessed(state.iterations() * s.two.boundary.edge_count());
  state.counters["pairs"] = static_cast<double>(pairs.size());
}
BENCHMARK(BM_SelfContactBroadPhase)->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond);

void BM_SelfContactBarrier(benchmark::State& state) {
  const StackedSquares s(static_cast<int>(state.range(0)));
  BroadPhaseGrid grid;
  std::vector<PointEdgePair> pairs;
  swept_point_edge_candidates(s.two.boundary, s.x, s.p, 1.0, 0.01, grid, pairs);
  const SelfContactParams params;
  VecX g = VecX::Zero(s.x.size());
  std::vector<PointEdgeHessian> hessians;
  PairSumScratch scratch;  // as the step's: the sums over pairs on the threads
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        self_contact_energy(s.two.boundary, s.two.mesh.rest, pairs, s.x, params, &scratch));
    hessians.clear();
    add_self_contact_gradient_hessian(s.two.boundary, s.two.mesh.rest, pairs, s.x, params, 1.0, g,
                                      hessians, &scratch);
    benchmark::DoNotOptimize(self_contact_step(s.two.boundary, pairs, s.x, s.p, 1.0));
  }
  state.SetItemsProcessed(state.iterations() * s.two.boundary.edge_count());
  state.counters["active"] = static_cast<double>(hessians.size());
}
BENCHMARK(BM_SelfContactBarrier)->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace invfree

// INVFREE_THREADS sets the core's thread count here too (1 to 256; otherwise every core),
// e.g. `INVFREE_THREADS=1 invfree_bench --benchmark_filter=LdltSolve`.
int main(int argc, char** argv) {
  if (const char* value = std::getenv("INVFREE_THREADS"))
    if (const int n = std::atoi(value); n >= 1 && n <= 256) invfree::set_thread_count(n);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
