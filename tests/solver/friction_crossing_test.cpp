// The line search's friction crossing stop (core/friction_crossing.h): which nodes stop at
// zero slip, and that no stop ever squeezes a triangle below the inversion filter's 10%.
#include "solver/friction_crossing.h"

#include <gtest/gtest.h>

#include <random>

#include "potential/incremental_potential.h"
#include "scene/mesh.h"

namespace invfree {
namespace {

double signed_area(const VecX& x, const std::array<int, 3>& t) {
  const Vec2 a = x.segment<2>(2 * t[1]) - x.segment<2>(2 * t[0]);
  const Vec2 b = x.segment<2>(2 * t[2]) - x.segment<2>(2 * t[0]);
  return a.x() * b.y() - a.y() * b.x();
}

struct Fixture {
  Mesh mesh;
  StepProblem p;
  VecX rest;
  explicit Fixture(int n_seg) : mesh(square_mesh(1.0, n_seg)) {
    rest.resize(2 * mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i) rest.segment<2>(2 * i) = mesh.rest[i];
    p.mesh = &mesh;
    p.x_start = rest;
    p.friction.on = true;
    p.friction.eps_u = 1e-5;
    p.friction.weight.assign(mesh.node_count(), 0.0);
  }
};

TEST(FrictionCrossing, StopsSlidingNodesThatTheStepCarriesAcrossZeroSlip) {
  Fixture f(2);  // nodes 3i + j; the bottom row is 0, 3, 6
  for (int i : {0, 3, 6}) f.p.friction.weight[i] = 1.0;
  const double eps = f.p.friction.eps_u;
  VecX z = f.rest, trial = f.rest;
  auto slip = [&](int node, double u0, double u1) {
    z[2 * node] += u0;
    trial[2 * node] += u1;
  };
  slip(3, 5 * eps, -5 * eps);    // crosses and lands beyond the window: stops
  slip(0, 5 * eps, -0.5 * eps);  // lands inside the window, where friction is smooth
  slip(6, 5 * eps, 2 * eps);     // keeps its side
  slip(4, 5 * eps, -5 * eps);    // no friction on this node
  trial[2 * 3 + 1] += 1e-3;      // and a vertical move, which a stop keeps
  const VecX straight = trial;
  FrictionCrossingScratch scratch;
  EXPECT_EQ(stop_friction_crossings(f.p, z, trial, scratch), 1);
  EXPECT_EQ(trial[2 * 3], f.p.x_start[2 * 3]);
  for (int i = 0; i < f.mesh.node_count(); ++i) {
    EXPECT_EQ(trial[2 * i + 1], straight[2 * i + 1]) << "node " << i;
    if (i != 3) {
      EXPECT_EQ(trial[2 * i], straight[2 * i]) << "node " << i;
    }
  }
  VecX again = straight;  // friction off: nothing to stop
  f.p.friction.on = false;
  EXPECT_EQ(stop_friction_crossings(f.p, z, again, scratch), 0);
  EXPECT_EQ(again, straight);
}

// Random states and steps, every node a sliding friction node, the step cut by the
// inversion filter: every triangle with a stopped node keeps at least 10% of its area, and
// every node is either where the step put it or, if it crossed, at zero slip.
TEST(FrictionCrossing, NeverSqueezesATriangleBelowTheFilter) {
  Fixture f(4);
  std::fill(f.p.friction.weight.begin(), f.p.friction.weight.end(), 1.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  FrictionCrossingScratch scratch;
  int stopped = 0, given_back = 0;
  for (int trial_no = 0; trial_no < 400; ++trial_no) {
    const int dofs = 2 * f.mesh.node_count();
    VecX z = f.rest, p(dofs);
    for (int k = 0; k < dofs; ++k) {
      z[k] += 0.03 * unit(rng);
      p[k] = 0.4 * unit(rng);
    }
    for (int i = 0; i < f.mesh.node_count(); ++i) f.p.x_start[2 * i] = z[2 * i] - 0.1 * unit(rng);
    const double alpha = std::min(1.0, inversion_free_step(f.mesh, z, p));
    const VecX straight = z + alpha * p;
    VecX trial = straight;
    int crossings = 0;
    for (int i = 0; i < f.mesh.node_count(); ++i) {
      const double u0 = z[2 * i] - f.p.x_start[2 * i], u1 = straight[2 * i] - f.p.x_start[2 * i];
      if (u0 * u1 < 0.0 && std::abs(u1) >= f.p.friction.eps_u) ++crossings;
    }
    const int count = stop_friction_crossings(f.p, z, trial, scratch);
    ASSERT_LE(count, crossings);
    stopped += count;
    given_back += crossings - count;
    int at_zero = 0;
    for (int i = 0; i < f.mesh.node_count(); ++i) {
      ASSERT_EQ(trial[2 * i + 1], straight[2 * i + 1]);
      if (trial[2 * i] != straight[2 * i]) {
        ASSERT_EQ(trial[2 * i], f.p.x_start[2 * i]);
        ++at_zero;
      }
    }
    ASSERT_EQ(at_zero, count);
    // (A triangle without a stopped node is the straight point's: the filter's business,
    // at its alpha exactly 10% up to rounding.)
    for (const auto& t : f.mesh.triangles) {
      const bool touched = trial[2 * t[0]] != straight[2 * t[0]] ||
                           trial[2 * t[1]] != straight[2 * t[1]] ||
                           trial[2 * t[2]] != straight[2 * t[2]];
      if (touched) {
        ASSERT_GE(signed_area(trial, t), 0.1 * signed_area(z, t)) << "trial " << trial_no;
      }
    }
  }
  // Both paths were exercised: stops kept, and stops given back to spare a triangle.
  EXPECT_GT(stopped, 0);
  EXPECT_GT(given_back, 0);
}

}  // namespace
}  // namespace invfree
