// The study's accuracy measure: RMS node-position error relative to the side, the node
// map between nested meshes, and the log-log slope fit.
#include "app/study/error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/mesh.h"

namespace invfree {
namespace {

VecX positions(const Mesh& m) {
  VecX x(2 * m.node_count());
  for (int i = 0; i < m.node_count(); ++i) x.segment<2>(2 * i) = m.rest[i];
  return x;
}

TEST(ErrorMetric, UniformShiftGivesItsLengthOverTheSide) {
  const Mesh m = square_mesh(2.0, 3);
  const VecX a = positions(m);
  VecX b = a;
  for (int i = 0; i < m.node_count(); ++i) b.segment<2>(2 * i) += Vec2(0.3, 0.4);  // |d| = 0.5
  EXPECT_NEAR(rms_position_error({a, a}, {a, b}, 2.0), std::sqrt(0.5 * 0.25) / 2.0, 1e-14)
      << "half the samples are off by 0.5: RMS = sqrt(0.125), over side 2";
  EXPECT_NEAR(rms_position_error({b}, {a}, 2.0), 0.25, 1e-14);
  EXPECT_EQ(rms_position_error({a}, {a}, 2.0), 0.0);
}

TEST(ErrorMetric, IsRootMeanSquareOverNodes) {
  VecX a = VecX::Zero(8), b = VecX::Zero(8);
  b[0] = 1.0;  // one node of four off by 1: RMS = sqrt(1/4)
  EXPECT_NEAR(rms_position_error({a}, {b}, 1.0), 0.5, 1e-15);
}

TEST(ErrorMetric, MismatchedRunsAreNotANumber) {
  const VecX a = VecX::Zero(8), b = VecX::Zero(10);
  EXPECT_TRUE(std::isnan(rms_position_error({a}, {b}, 1.0)));
  EXPECT_TRUE(std::isnan(rms_position_error({a, a}, {a}, 1.0)))
      << "a run that stopped early has fewer samples";
  EXPECT_TRUE(std::isnan(rms_position_error({}, {}, 1.0)));
}

TEST(ErrorMetric, NestedNodeMapPicksTheSameMaterialPoints) {
  const Mesh coarse = square_mesh(1.0, 2), fine = square_mesh(1.0, 8);
  const std::vector<int> map = nested_node_map(2, 8);
  ASSERT_EQ(static_cast<int>(map.size()), coarse.node_count());
  for (int i = 0; i < coarse.node_count(); ++i)
    EXPECT_LT((coarse.rest[i] - fine.rest[map[i]]).norm(), 1e-14) << "coarse node " << i;
  EXPECT_TRUE(nested_node_map(3, 8).empty());
  EXPECT_TRUE(nested_node_map(4, 2).empty());
  // With the map, identical motion on both meshes has zero error.
  EXPECT_EQ(rms_position_error({positions(coarse)}, {positions(fine)}, 1.0, map), 0.0);
  EXPECT_TRUE(std::isnan(rms_position_error({positions(coarse)}, {positions(fine)}, 1.0)))
      << "without the map the node counts differ";
}

TEST(LogLogSlope, RecoversThePowerAndSkipsInvalidPoints) {
  std::vector<double> x = {0.04, 0.02, 0.01, 0.005}, y;
  for (double v : x) y.push_back(3.0 * std::pow(v, 1.5));
  EXPECT_NEAR(loglog_slope(x, y), 1.5, 1e-12);
  x.push_back(0.001);
  y.push_back(std::nan(""));  // a failed run
  x.push_back(-1.0);
  y.push_back(1.0);
  EXPECT_NEAR(loglog_slope(x, y), 1.5, 1e-12);
  EXPECT_TRUE(std::isnan(loglog_slope({1.0}, {2.0})));
  EXPECT_TRUE(std::isnan(loglog_slope({1.0, 1.0}, {2.0, 3.0}))) << "all x equal: no slope";
}

}  // namespace
}  // namespace invfree
