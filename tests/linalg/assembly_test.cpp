// The performance paths give the same answers as the plain ones: the structured
// per-triangle kernel equals the dense chain rule; the Hessian's pattern and slots are a
// triplet build's; the parallel assembly, energy and whole simulation are bit-identical
// for any number of threads; the colouring plan never puts two chunks that share a node
// in one colour; the thread count is the core's setting alone, never the environment's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <thread>

#include "linalg/parallel.h"
#include "material/models.h"
#include "material/triangle_elasticity.h"
#include "potential/incremental_potential.h"
#include "scene_io/builtin_scenes.h"
#include "simulation.h"
#include "solver/step_workspace.h"
#include "tests/test_support.h"

namespace invfree {
namespace {

const Lame kLame = lame_from_young_poisson(1e5, 0.4);

bool same_bits(const VecX& a, const VecX& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

TEST(TriangleKernel, MatchesTheDenseChainRule) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (Model m : {Model::NeoHookean, Model::StableNeoHookean, Model::Arap, Model::Linear}) {
    visit_model(m, [&](auto model) {
      using M = decltype(model);
      for (const Mat2& F : test::sample_deformation_gradients(model_allows_inversion(m), 150)) {
        if (m == Model::Arap) {
          const PolarSvd s = polar_svd(F);
          if (std::abs(s.sigma(0) + s.sigma(1)) < 0.05) continue;  // ARAP's singular set
        }
        Mat2 IB;
        IB << 1 + 0.3 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 1 + 0.3 * u(rng);
        const Mat46 dFdx = deformation_gradient_jacobian(IB);
        for (auto proj :
             {HessianProjection::Diagonal, HessianProjection::Full, HessianProjection::None}) {
          Vec6 g;
          Mat6 H;
          TriangleElasticity<M>::gradient_hessian(F, IB, 0.7, kLame, proj, g, H);
          const Vec6 g_ref = TriangleElasticity<M>::gradient(F, dFdx, 0.7, kLame);
          const Mat6 H_ref = TriangleElasticity<M>::hessian(F, dFdx, 0.7, kLame, proj);
          EXPECT_LT((g - g_ref).norm(), 1e-12 * std::max(1.0, g_ref.norm())) << model_name(m);
          EXPECT_LT((H - H_ref).norm(), 1e-11 * std::max(1.0, H_ref.norm()))
              << model_name(m) << " " << projection_name(proj);
          EXPECT_TRUE(H == H.transpose()) << "the assembled Hessian must be exactly symmetric";
        }
      }
    });
  }
}

TEST(AssemblyPlan, NoTwoChunksOfAColourShareANode) {
  for (int n_seg : {1, 5, 16, 33, 64}) {
    const Mesh mesh = square_mesh(1.0, n_seg);
    const SparseHessian h = build_sparse_hessian(mesh, true);
    int chunks = 0;
    for (int c = 0; c < h.colour_count(); ++c) {
      std::vector<int> owner(mesh.node_count(), -1);
      for (int k = h.colour_begin[c]; k < h.colour_begin[c + 1]; ++k) {
        const int chunk = h.chunk_order[k];
        ++chunks;
        const int begin = chunk * h.chunk_size;
        const int end = std::min(mesh.triangle_count(), begin + h.chunk_size);
        for (int t = begin; t < end; ++t)
          for (int v : mesh.triangles[t]) {
            EXPECT_TRUE(owner[v] == -1 || owner[v] == chunk)
                << "n_seg " << n_seg << " colour " << c;
            owner[v] = chunk;
          }
      }
    }
    EXPECT_EQ(chunks * h.chunk_size >= mesh.triangle_count(), true);
    EXPECT_LE(h.colour_count(), 8) << "the square mesh should need only a few colours";
  }
}

// The Hessian's pattern, written straight into the compressed arrays, is the one Eigen
// builds from every entry the terms touch (a triplet list, summed), and each slot the
// assembly writes to is that entry's place in it: on meshes with and without the ceiling's
// unknown, with extra node pairs (a repeat, a pair already sharing a triangle, a node with
// itself) and with a node that belongs to no triangle.
TEST(SparseHessianPattern, MatchesATripletBuildAndItsSlots) {
  struct Case {
    Mesh mesh;
    bool ceiling;
    std::vector<std::array<int, 2>> pairs;
  };
  std::vector<Case> cases;
  cases.push_back({square_mesh(1.0, 1), false, {}});
  cases.push_back({square_mesh(1.0, 7), true, {}});
  cases.push_back({square_mesh(2.0, 12), true, {{0, 13}, {13, 0}, {5, 5}, {0, 1}, {168, 3}}});
  Mesh lonely = square_mesh(1.0, 3);
  lonely.rest.push_back(Vec2(5.0, 5.0));  // a node in no triangle
  cases.push_back({lonely, true, {{2, 9}}});
  for (const Case& k : cases) {
    const int n = static_cast<int>(k.mesh.rest.size());
    const int dofs = 2 * n + (k.ceiling ? 1 : 0);
    std::vector<Eigen::Triplet<double>> entries;
    auto block = [&](int i, int j) {
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) entries.emplace_back(2 * i + a, 2 * j + b, 1.0);
    };
    for (const auto& tri : k.mesh.triangles)
      for (int i : tri)
        for (int j : tri) block(i, j);
    for (int i = 0; i < n; ++i) block(i, i);
    for (const auto& p : k.pairs) {
      block(p[0], p[1]);
      block(p[1], p[0]);
    }
    if (k.ceiling) {
      entries.emplace_back(2 * n, 2 * n, 1.0);
      for (int i = 0; i < n; ++i) {
        entries.emplace_back(2 * i + 1, 2 * n, 1.0);
        entries.emplace_back(2 * n, 2 * i + 1, 1.0);
      }
    }
    Eigen::SparseMatrix<double> reference(dofs, dofs);
    reference.setFromTriplets(entries.begin(), entries.end());
    reference.makeCompressed();

    const SparseHessian h = build_sparse_hessian(k.mesh, k.ceiling, k.pairs);
    ASSERT_EQ(h.matrix.rows(), dofs);
    ASSERT_TRUE(h.matrix.isCompressed());
    ASSERT_EQ(h.matrix.nonZeros(), reference.nonZeros());
    EXPECT_TRUE(std::equal(reference.outerIndexPtr(), reference.outerIndexPtr() + dofs + 1,
                           h.matrix.outerIndexPtr()));
    EXPECT_TRUE(std::equal(reference.innerIndexPtr(),
                           reference.innerIndexPtr() + reference.nonZeros(),
                           h.matrix.innerIndexPtr()));
    auto slot = [&](int row, int col) { return sparse_slot(reference, row, col); };
    for (int t = 0; t < k.mesh.triangle_count(); ++t)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          const auto& tri = k.mesh.triangles[t];
          ASSERT_EQ(h.triangle_slots[36 * t + 6 * a + b],
                    slot(2 * tri[a / 2] + a % 2, 2 * tri[b / 2] + b % 2))
              << "triangle " << t << " entry " << a << "," << b;
        }
    for (int i = 0; i < dofs; ++i) EXPECT_EQ(h.diagonal_slots[i], slot(i, i));
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(h.node_xy_slots[2 * i], slot(2 * i, 2 * i + 1));
      EXPECT_EQ(h.node_xy_slots[2 * i + 1], slot(2 * i + 1, 2 * i));
      if (k.ceiling) {
        EXPECT_EQ(h.ceiling_slots[2 * i], slot(2 * i + 1, 2 * n));
        EXPECT_EQ(h.ceiling_slots[2 * i + 1], slot(2 * n, 2 * i + 1));
      }
    }
    EXPECT_EQ(h.ceiling_dof, k.ceiling ? 2 * n : -1);
    for (int p = 0; p < h.matrix.nonZeros(); ++p) EXPECT_EQ(h.matrix.valuePtr()[p], 0.0);
  }
}

// A compressed, jittered state with ground and ceiling contacts and friction active.
struct Problem {
  Simulation sim;
  VecX z;
  explicit Problem(int n_seg) {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = n_seg;
    sim = make_simulation(s);
    for (int k = 0; k < 120; ++k) EXPECT_EQ(step(sim).status, StepStatus::Ok);
    // The step's problem as the solver sees it, at a perturbed state.
    step(sim);
    z.resize(sim.workspace->problem.dof_count());
    z.head(sim.x.size()) = sim.x;
    z[sim.x.size()] = sim.ceiling_y;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1e-4, 1e-4);
    for (int i = 0; i < sim.x.size(); ++i) z[i] += u(rng) * (i % 2 ? 0.1 : 1.0);
  }
};

TEST(ParallelAssembly, BitIdenticalForAnyThreadCount) {
  Problem p(48);  // 4608 triangles: the assembly runs in parallel colours
  ASSERT_GE(p.sim.mesh.triangle_count(), 2048);
  std::vector<VecX> gradients, values;
  std::vector<double> energies;
  for (int threads : {1, 2, 3, 4}) {
    set_thread_count(threads);
    VecX g;
    SparseHessian h = p.sim.workspace->newton.hessian;
    ip_gradient_hessian(p.sim.workspace->problem, p.sim.workspace->caches, p.z, g, h);
    gradients.push_back(g);
    values.push_back(Eigen::Map<const VecX>(h.matrix.valuePtr(), h.matrix.nonZeros()));
    energies.push_back(ip_energy(p.sim.workspace->problem, p.sim.workspace->caches, p.z));
  }
  set_thread_count(0);
  for (std::size_t k = 1; k < gradients.size(); ++k) {
    EXPECT_TRUE(same_bits(gradients[k], gradients[0]))
        << "gradient differs with " << k + 1 << " threads";
    EXPECT_TRUE(same_bits(values[k], values[0])) << "Hessian differs with " << k + 1 << " threads";
    EXPECT_EQ(std::memcmp(&energies[k], &energies[0], sizeof(double)), 0)
        << "energy, " << k + 1 << " threads";
  }
  // And the parallel energy is the sum it should be (against a plain serial sum).
  EXPECT_GT(std::abs(energies[0]), 0.0);
}

TEST(ParallelAssembly, WholeRunBitIdenticalForAnyThreadCount) {
  auto run = [](int threads) {
    set_thread_count(threads);
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = 40;  // 3200 triangles: parallel assembly and PCG products
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 150; ++k) EXPECT_EQ(step(sim).status, StepStatus::Ok);
    return sim.x;
  };
  const VecX one = run(1), two = run(2), three = run(3);
  set_thread_count(0);
  EXPECT_TRUE(same_bits(one, two));
  EXPECT_TRUE(same_bits(one, three));
}

// The fold at n_seg 48 with self-contact: contact pairs come and go, the pattern grows,
// PCG's factor is renewed and the tree-scheduled LDL^T (tens of tasks in levels) solves
// on 1, 2, 3 and 5 threads. Every one gives the same bits; and the contact really acted
// (the run without it ends elsewhere).
TEST(ParallelAssembly, SelfContactFoldBitIdenticalForAnyThreadCount) {
  auto run = [](int threads, bool self_contact) {
    set_thread_count(threads);
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = 48;
    s.has_self_contact = self_contact;
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 280; ++k) {
      const StepReport r = step(sim);
      EXPECT_EQ(r.status, StepStatus::Ok) << "step " << k << ": " << r.message;
      if (r.status != StepStatus::Ok) break;
    }
    return sim.x;
  };
  const VecX one = run(1, true);
  for (int threads : {2, 3, 5})
    EXPECT_TRUE(same_bits(one, run(threads, true))) << threads << " threads";
  const VecX without = run(2, false);
  set_thread_count(0);
  EXPECT_GT((one - without).lpNorm<Eigen::Infinity>(), 1e-6);
}

// Two simulations stepping at the same time on two threads share the one pool (render
// --compare's two runs, Python threads with the GIL released): each gets the bits it gets
// alone. Before the pool took one run at a time (the other inline), the second caller
// overwrote the first's run and both waited for each other's tasks for ever.
TEST(ThreadPool, TwoSimulationsSteppingAtOnceGetTheirOwnBits) {
  set_thread_count(2);
  auto run = [](int n_seg) {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.n_seg = n_seg;  // >= 2,048 triangles: parallel assembly, products and LDL^T levels
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 120; ++k)
      if (step(sim).status != StepStatus::Ok) break;
    return sim.x;
  };
  const VecX alone_a = run(40), alone_b = run(36);
  VecX a, b;
  for (int round = 0; round < 3; ++round) {
    std::thread other([&] { b = run(36); });
    a = run(40);
    other.join();
    EXPECT_TRUE(same_bits(a, alone_a)) << "round " << round;
    EXPECT_TRUE(same_bits(b, alone_b)) << "round " << round;
  }
  set_thread_count(0);
}

// INVFREE_THREADS is the command line's (app/main.cpp): the core never reads it.
TEST(ThreadPool, SizedByItsSettingAlone) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const char* before = std::getenv("INVFREE_THREADS");
  const std::string saved = before ? before : "";
  setenv("INVFREE_THREADS", std::to_string(cores + 1).c_str(), 1);
  set_thread_count(3);
  EXPECT_EQ(thread_count(), 3);
  set_thread_count(0);  // the default: one per core
  EXPECT_EQ(thread_count(), cores);
  if (before)
    setenv("INVFREE_THREADS", saved.c_str(), 1);
  else
    unsetenv("INVFREE_THREADS");
}

}  // namespace
}  // namespace invfree
