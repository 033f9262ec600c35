// Whole-simulation checks: the reference demo keeps every invariant at every step and
// comes to rest; frictionless compression between plates reaches the analytic
// plane-strain equilibrium; failures are reported, not looped on; runs are bit-identical.
#include "simulation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"

namespace invfree {
namespace {

// Independent invariant check (does not reuse the library's own checker).
void expect_invariants(const Simulation& sim, long step) {
  ASSERT_TRUE(sim.x.allFinite() && sim.v.allFinite()) << "step " << step;
  for (const auto& t : sim.mesh.triangles) {
    const Vec2 a = sim.x.segment<2>(2 * t[1]) - sim.x.segment<2>(2 * t[0]);
    const Vec2 b = sim.x.segment<2>(2 * t[2]) - sim.x.segment<2>(2 * t[0]);
    ASSERT_GT(a.x() * b.y() - a.y() * b.x(), 0.0) << "inverted triangle at step " << step;
  }
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    const double y = sim.x[2 * i + 1];
    if (sim.scene.has_ground) {
      ASSERT_GT(y, sim.scene.ground_y) << "step " << step;
    }
    if (sim.scene.has_ceiling) {
      ASSERT_LT(y, sim.ceiling_y) << "step " << step;
    }
  }
}

double max_speed(const Simulation& sim) {
  double v = 0;
  for (int i = 0; i < sim.mesh.node_count(); ++i) v = std::max(v, sim.v.segment<2>(2 * i).norm());
  return v;
}

TEST(Compress, KeepsEveryInvariantAndEndsAtRest) {
  Simulation sim = make_simulation(*load_builtin_scene("compress").scene);
  double min_height = 1.0;
  for (int k = 0; k < 600; ++k) {
    const StepReport r = step(sim);
    ASSERT_EQ(r.status, StepStatus::Ok) << "step " << k << ": " << r.message;
    ASSERT_LT(r.residual, sim.scene.tol);
    expect_invariants(sim, sim.step_count);
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < sim.mesh.node_count(); ++i) {
      lo = std::min(lo, sim.x[2 * i + 1]);
      hi = std::max(hi, sim.x[2 * i + 1]);
    }
    min_height = std::min(min_height, hi - lo);
  }
  // The ceiling reached its stop (within Newton's tolerance on its position) ...
  EXPECT_LE(sim.ceiling_nominal, sim.scene.ceiling_stop);
  EXPECT_NEAR(sim.ceiling_y, sim.ceiling_nominal, sim.scene.tol * sim.scene.h);
  // ... the square is squashed to under a third of its height between ceiling and ground ...
  EXPECT_LT(min_height, 0.31);
  EXPECT_GT(min_height, 0.25);
  // ... and everything has come to rest.
  EXPECT_LT(max_speed(sim), 1e-2);
}

TEST(Drop, LandsAndComesToRest) {
  Simulation sim = make_simulation(*load_builtin_scene("drop").scene);
  for (int k = 0; k < 300; ++k) {
    ASSERT_EQ(step(sim).status, StepStatus::Ok);
    expect_invariants(sim, sim.step_count);
  }
  EXPECT_LT(max_speed(sim), 1e-2);
  const double gap = min_plane_gap(sim);
  EXPECT_GT(gap, 0.0);
  EXPECT_LT(gap, sim.scene.dhat);  // resting on the barrier
}

// Horizontal stretch s at which a neo-Hookean body with vertical stretch t is
// traction-free sideways: dPsi/ds = mu (s - 1/s) + lambda ln(s t)/s = 0
// <=> mu (s^2 - 1) + lambda ln(s t) = 0, solved by bisection (monotone in s).
double plane_strain_stretch(double t, const Lame& l) {
  double lo = 1e-3, hi = 10.0;
  for (int k = 0; k < 200; ++k) {
    const double s = 0.5 * (lo + hi);
    (l.mu * (s * s - 1) + l.lambda * std::log(s * t) > 0 ? hi : lo) = s;
  }
  return 0.5 * (lo + hi);
}

TEST(PlateCompression, ReachesAnalyticPlaneStrainEquilibrium) {
  SceneDef s;
  s.name = "plates";
  s.n_seg = 1;  // with one cell the homogeneous state is an exact discrete equilibrium
  s.has_gravity = false;
  s.friction = 0.0;
  s.ground_y = -0.5 - 0.005;
  s.ceiling_y = 0.5 + 0.005;
  s.ceiling_velocity = -0.2;
  s.ceiling_stop = 0.31;  // one step down to 0.305, then it stays
  s.h = 1.0;              // quasi-static
  s.tol = 1e-12;
  ASSERT_EQ(validate_scene(s), "");
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 60; ++k)
    ASSERT_EQ(step(sim).status, StepStatus::Ok) << k << " " << step(sim).message;
  ASSERT_LT(max_speed(sim), 1e-11);
  // Measured vertical stretch, and the homogeneous F of every triangle.
  const auto& x = sim.x;
  const double height = x[3] - x[1];  // node 1 is top-left, node 0 bottom-left
  const double width = x[4] - x[0];   // node 2 is bottom-right
  const double sy = height / s.side, sx = width / s.side;
  EXPECT_LT(sy, 0.81);  // squeezed between ceiling 0.305 and ground -0.505, minus the barrier gaps
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    const auto& tri = sim.mesh.triangles[t];
    Mat2 ds;
    ds.col(0) = x.segment<2>(2 * tri[1]) - x.segment<2>(2 * tri[0]);
    ds.col(1) = x.segment<2>(2 * tri[2]) - x.segment<2>(2 * tri[0]);
    const Mat2 F = ds * sim.mesh.rest_shape_inverse[t];
    EXPECT_NEAR(F(0, 1), 0.0, 1e-9);
    EXPECT_NEAR(F(1, 0), 0.0, 1e-9);
    EXPECT_NEAR(F(1, 1), sy, 1e-9);
  }
  EXPECT_NEAR(sx, plane_strain_stretch(sy, s.lame), 1e-8);
}

TEST(Failures, NewtonCapIsReportedAndStateKept) {
  SceneDef s = *load_builtin_scene("compress").scene;
  s.max_newton = 1;
  s.tol = 1e-14;
  Simulation sim = make_simulation(s);
  const VecX before = sim.x;
  const StepReport r = step(sim);
  EXPECT_EQ(r.status, StepStatus::NewtonFailed);
  EXPECT_NE(r.message.find("iteration cap"), std::string::npos);
  EXPECT_EQ(sim.step_count, 0);
  EXPECT_TRUE(sim.x == before);
}

TEST(Determinism, RepeatedRunsAreBitIdentical) {
  auto run = [] {
    Simulation sim = make_simulation(*load_builtin_scene("compress").scene);
    for (int k = 0; k < 250; ++k) step(sim);
    return sim.x;
  };
  const VecX a = run(), b = run();
  EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof(double) * a.size()), 0);
}

TEST(UpdateScene, MaterialChangeMidRunKeepsInvariants) {
  Simulation sim = make_simulation(*load_builtin_scene("compress").scene);
  for (int k = 0; k < 200; ++k) step(sim);
  SceneDef soft = sim.scene;
  soft.lame = lame_from_young_poisson(1e4, 0.45);
  update_scene(sim, soft);
  EXPECT_EQ(sim.step_count, 200);  // state kept
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(step(sim).status, StepStatus::Ok);
    expect_invariants(sim, sim.step_count);
  }
}

TEST(InvertibleModels, StepThroughCompressWithoutFailing) {
  for (Model m : {Model::Linear, Model::Arap, Model::StableNeoHookean}) {
    SceneDef s = *load_builtin_scene("compress").scene;
    s.model = m;
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 150; ++k)
      ASSERT_EQ(step(sim).status, StepStatus::Ok) << model_name(m) << " step " << k;
  }
}

TEST(SymplecticEuler, DropsUnderGravityLikeFreeFall) {
  SceneDef s = *load_builtin_scene("drop").scene;
  s.integrator = Integrator::SymplecticEuler;
  s.h = 1e-4;
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 1000; ++k) ASSERT_EQ(step(sim).status, StepStatus::Ok);
  // 0.1 s of free fall from rest: every node moved down by g t^2 / 2 (+ O(h)).
  const double expected = 0.5 * 9.81 * 0.1 * 0.1;
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    EXPECT_NEAR(sim.mesh.rest[i].y() - sim.x[2 * i + 1], expected, 1e-3);
}

}  // namespace
}  // namespace invfree
