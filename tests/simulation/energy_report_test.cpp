// core/energy_report.h: each energy against a state whose value is known by hand.
#include "energy_report.h"

#include <gtest/gtest.h>

#include "scene_io/builtin_scenes.h"

namespace invfree {
namespace {

TEST(EnergyReport, EachTermIsTheHandValue) {
  SceneDef s = *load_builtin_scene("drop").scene;
  Simulation sim = make_simulation(s);
  double mass = 0.0;
  for (double m : sim.node_mass) mass += m;
  // At rest and undeformed: no kinetic or elastic energy.
  sim.v.setZero();
  EnergyReport e = energy_report(sim);
  EXPECT_EQ(e.kinetic, 0.0);
  EXPECT_NEAR(e.elastic, 0.0, 1e-9);
  // Moving as a whole at (3, 4) m/s: 1/2 M 25.
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.v.segment<2>(2 * i) = Vec2(3.0, 4.0);
  e = energy_report(sim);
  EXPECT_NEAR(e.kinetic, 0.5 * mass * 25.0, 1e-9 * mass);
  // Lifted by 1 m: gravity's potential grows by M |g| (g points down).
  const double g0 = e.gravitational;
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.x[2 * i + 1] += 1.0;
  e = energy_report(sim);
  EXPECT_NEAR(e.gravitational - g0, -mass * s.gravity.y(), 1e-9 * mass);
  EXPECT_EQ(e.contact, 0.0);  // far from the ground
  // Stretched by 10% along x: elastic energy appears; near the ground: contact energy.
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.x[2 * i] *= 1.1;
  EXPECT_GT(energy_report(sim).elastic, 0.0);
  ASSERT_TRUE(s.has_ground);
  double lowest = sim.x[1];
  for (int i = 0; i < sim.mesh.node_count(); ++i) lowest = std::min(lowest, sim.x[2 * i + 1]);
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    sim.x[2 * i + 1] += s.ground_y + 0.5 * s.dhat - lowest;
  EXPECT_GT(energy_report(sim).contact, 0.0);
  EXPECT_NEAR(energy_report(sim).total(),
              energy_report(sim).kinetic + energy_report(sim).elastic +
                  energy_report(sim).gravitational + energy_report(sim).contact,
              1e-12);
}

}  // namespace
}  // namespace invfree
