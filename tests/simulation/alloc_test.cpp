// A step allocates nothing: this executable replaces malloc and its relatives (which
// operator new, Eigen and CHOLMOD all end up in) with counting versions, warms a
// simulation up for a few steps (first-use buffers, CHOLMOD's workspace pool) and then
// requires zero calls to the allocator for the rest of a whole run, for every solver
// backend, a scene without ceiling and the explicit integrator. Worker threads count too.
#include <gtest/gtest.h>
#include <link.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "linalg/parallel.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
std::atomic<long> g_runtime_allocations{0};

// Two runtimes that CHOLMOD's supernodal factorisation calls allocate small records of
// their own on every call: libgomp a team for each OpenMP region it runs on one thread
// (CHOLMOD opens such regions per supernode), OpenBLAS a job table for each threaded
// level-3 call. Their allocations are told apart by the caller's address.
struct Range {
  std::uintptr_t begin = 0, end = 0;
};
Range g_runtime[2];
int find_runtimes(dl_phdr_info* info, std::size_t, void*) {
  if (!info->dlpi_name) return 0;
  const int which = std::strstr(info->dlpi_name, "libgomp")       ? 0
                    : std::strstr(info->dlpi_name, "libopenblas") ? 1
                                                                  : -1;
  if (which < 0) return 0;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const auto& ph = info->dlpi_phdr[i];
    if (ph.p_type == PT_LOAD && (ph.p_flags & PF_X)) {
      g_runtime[which].begin = info->dlpi_addr + ph.p_vaddr;
      g_runtime[which].end = g_runtime[which].begin + ph.p_memsz;
    }
  }
  return 0;
}

inline void count(void* caller) {
  if (!g_counting.load(std::memory_order_relaxed)) return;
  const auto a = reinterpret_cast<std::uintptr_t>(caller);
  if ((a >= g_runtime[0].begin && a < g_runtime[0].end) ||
      (a >= g_runtime[1].begin && a < g_runtime[1].end))
    g_runtime_allocations.fetch_add(1, std::memory_order_relaxed);
  else
    g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* malloc(std::size_t n) {
  count(__builtin_return_address(0));
  return __libc_malloc(n);
}
void* calloc(std::size_t a, std::size_t b) {
  count(__builtin_return_address(0));
  return __libc_calloc(a, b);
}
void* realloc(void* p, std::size_t n) {
  count(__builtin_return_address(0));
  return __libc_realloc(p, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n) {
  count(__builtin_return_address(0));
  return __libc_memalign(alignment, n);
}
void* memalign(std::size_t alignment, std::size_t n) {
  count(__builtin_return_address(0));
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t n) {
  count(__builtin_return_address(0));
  void* p = __libc_memalign(alignment, n);
  if (!p) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void free(void* p) {
  __libc_free(p);
}
}

namespace invfree {
namespace {

struct Counts {
  long ours = 0;                   // outside the two runtimes, in any step: must be 0
  long without_factorization = 0;  // anything at all in a step that reused the factor: must be 0
  long runtime = 0;                // libgomp / OpenBLAS records, in refactorising steps only
  long factorizations = 0;
};

Counts allocations_during_run(SceneDef scene, int warmup, int steps) {
  if (g_runtime[0].end == 0) dl_iterate_phdr(find_runtimes, nullptr);
  Simulation sim = make_simulation(scene);
  for (int k = 0; k < warmup; ++k) EXPECT_EQ(step(sim).status, StepStatus::Ok);
  Counts c;
  int failed_at = -1;
  for (int k = 0; k < steps && failed_at < 0; ++k) {
    g_allocations = 0;
    g_runtime_allocations = 0;
    g_counting = true;
    const StepReport r = step(sim);
    g_counting = false;
    if (r.status != StepStatus::Ok) failed_at = k;
    c.factorizations += r.factorizations;
    c.ours += g_allocations;
    if (r.factorizations == 0)
      c.without_factorization += g_allocations + g_runtime_allocations;
    else
      c.runtime += g_runtime_allocations;
  }
  EXPECT_EQ(failed_at, -1) << scene.name;
  return c;
}

TEST(NoAllocation, CountingAllocatorSeesAllocations) {
  g_allocations = 0;
  g_counting = true;
  VecX v(1000);  // Eigen's heap storage goes through malloc
  v.setZero();
  g_counting = false;
  EXPECT_GE(g_allocations.load(), 1) << "the counting allocator is not in use";
}

TEST(NoAllocation, ImplicitStepsWithEveryLinearSolver) {
  for (LinearSolverKind kind : {LinearSolverKind::Auto, LinearSolverKind::Ldlt,
                                LinearSolverKind::Cholmod, LinearSolverKind::Pcg}) {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = 12;
    s.linear_solver = kind;
    const Counts c = allocations_during_run(s, 3, 297);
    EXPECT_EQ(c.ours, 0) << linear_solver_name(kind);
    EXPECT_EQ(c.without_factorization, 0) << linear_solver_name(kind);
    if (kind != LinearSolverKind::Cholmod) {
      EXPECT_EQ(c.runtime, 0) << linear_solver_name(kind) << ": Eigen's LDL^T calls no runtime";
    }
  }
}

// A large mesh: parallel colours and products, METIS-ordered LDL^T with its scratch on the
// stack, and, with the CHOLMOD backend, CHOLMOD's own memory pooled
// (core/linalg/cholmod_backend.cpp): what remains there are the runtimes' records in the steps
// that refactorise, and a step that reuses the factor allocates nothing at all.
TEST(NoAllocation, LargeMeshWithParallelAssemblyAndCholmod) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.n_seg = 82;  // 13,778 unknowns: above the METIS and the 16k-stack thresholds' neighbourhood
  {
    SceneDef direct = s;
    direct.linear_solver = LinearSolverKind::Cholmod;
    const Counts c = allocations_during_run(direct, 3, 20);
    EXPECT_EQ(c.ours, 0) << "cholmod";
  }
  set_thread_count(2);
  const Counts c = allocations_during_run(s, 3, 147);
  set_thread_count(0);
  EXPECT_EQ(c.ours, 0);
  EXPECT_EQ(c.without_factorization, 0);
  EXPECT_LT(c.factorizations, 147 / 4) << "the factorisation should be reused across steps";
  std::printf(
      "  %ld refactorisations in 147 steps; runtime (OpenMP, OpenBLAS) allocations in them: %ld\n",
      c.factorizations, c.runtime);
}

TEST(NoAllocation, OtherScenesAndTheExplicitIntegrator) {
  SceneDef drop = *load_builtin_scene("drop").scene;
  drop.n_seg = 10;
  const Counts d = allocations_during_run(drop, 3, 200);
  EXPECT_EQ(d.ours + d.runtime, 0) << "drop";
  SceneDef explicit_euler = drop;
  explicit_euler.integrator = Integrator::SymplecticEuler;
  explicit_euler.h = 1e-4;
  const Counts e = allocations_during_run(explicit_euler, 3, 500);
  EXPECT_EQ(e.ours + e.runtime, 0) << "symplectic Euler";
}

}  // namespace
}  // namespace invfree
