#include "potential/self_contact_barrier.h"

#include <algorithm>
#include <cmath>

#include "material/psd_projection.h"
#include "potential/work_blocks.h"

namespace invfree {

namespace {

struct PairPoints {
  std::array<int, 3> nodes;  // node, edge[0], edge[1]
  Vec2 p, a, b;
};

PairPoints pair_points(const Boundary& boundary, const PointEdgePair& pair, const VecX& x) {
  const int i = boundary.nodes[pair.node];
  const auto& e = boundary.edges[pair.edge];
  return {{i, e[0], e[1]}, x.segment<2>(2 * i), x.segment<2>(2 * e[0]), x.segment<2>(2 * e[1])};
}

// The projected Hessian in a point-point regime, in closed form. With r = p - q (q the
// closest end), D = |r|^2 and K = [[1, -1], [-1, 1]] over the blocks of p and q:
//   H = B'' dD dD^T + B' d2D = K (x) M,   M = 4 B'' r r^T + 2 B' I,
// and K's eigenvalues are 2 and 0, so the projection clamps M's: 4 B'' D + 2 B' along r
// (positive: 2 B'' D + B' = a kappa'/2 (3 + 1/s + ln s) > 0 for s in (0, 1]) and
// 2 B' <= 0 across it. Result: (4 B'' + 2 B' / D) K (x) r r^T, what the eigen-
// decomposition gives (the tests compare them) at a fraction of its cost.
Mat6 point_point_projected(const Vec2& p, const Vec2& a, const Vec2& b, PointEdgeRegime regime,
                           double d2, double b1, double b2) {
  const bool first = regime == PointEdgeRegime::FirstEnd;
  const Vec2 r = p - (first ? a : b);
  const Mat2 block = std::max(4.0 * b2 + 2.0 * b1 / d2, 0.0) * r * r.transpose();
  const int q = first ? 2 : 4;
  Mat6 h = Mat6::Zero();
  h.block<2, 2>(0, 0) = h.block<2, 2>(q, q) = block;
  h.block<2, 2>(0, q) = h.block<2, 2>(q, 0) = -block;
  return h;
}

// The PSD projection of a Hessian that annihilates translations (H (t, t, t) = 0: D depends
// on differences of positions only). Its eigenvectors other than the two translations span
// the complement of the translations, here the orthonormal columns of Q (relative motions
// of p against a, and of both against b), so clamping the 4x4 Q^T H Q's eigenvalues and
// mapping back gives the 6x6 eigen-decomposition's result at about half its cost.
Mat6 project_psd_translation_free(const Mat6& h) {
  static const Eigen::Matrix<double, 6, 4> q = [] {
    const double s2 = std::sqrt(0.5), s6 = std::sqrt(1.0 / 6.0);
    Eigen::Matrix<double, 6, 4> m = Eigen::Matrix<double, 6, 4>::Zero();
    for (int k = 0; k < 2; ++k) {
      m(k, k) = s2;
      m(2 + k, k) = -s2;
      m(k, 2 + k) = m(2 + k, 2 + k) = s6;
      m(4 + k, 2 + k) = -2.0 * s6;
    }
    return m;
  }();
  const Mat4 reduced = q.transpose() * h * q;
  return q * project_psd<4>(reduced) * q.transpose();
}

}  // namespace

double point_edge_barrier(const Vec2& p, const Vec2& a, const Vec2& b,
                          const BarrierParams& barrier) {
  return barrier_value(point_edge_distance_squared(p, a, b), barrier);
}

Vec6 point_edge_barrier_gradient(const Vec2& p, const Vec2& a, const Vec2& b,
                                 const BarrierParams& barrier) {
  const PointEdgeRegime regime = point_edge_regime(p, a, b);
  const double d2 = point_edge_distance_squared(p, a, b, regime);
  if (d2 >= barrier.dhat) return Vec6::Zero();
  return barrier_derivative(d2, barrier) * point_edge_distance_squared_gradient(p, a, b, regime);
}

Mat6 point_edge_barrier_hessian(const Vec2& p, const Vec2& a, const Vec2& b,
                                const BarrierParams& barrier, bool project) {
  const PointEdgeRegime regime = point_edge_regime(p, a, b);
  const double d2 = point_edge_distance_squared(p, a, b, regime);
  if (d2 >= barrier.dhat) return Mat6::Zero();
  const double b1 = barrier_derivative(d2, barrier), b2 = barrier_second_derivative(d2, barrier);
  if (project && regime != PointEdgeRegime::Interior)
    return point_point_projected(p, a, b, regime, d2, b1, b2);
  const Vec6 g = point_edge_distance_squared_gradient(p, a, b, regime);
  const Mat6 h = b2 * g * g.transpose() + b1 * point_edge_distance_squared_hessian(p, a, b, regime);
  return project ? project_psd_translation_free(h) : h;
}

BarrierParams pair_barrier(const Boundary& boundary, const std::vector<Vec2>& rest,
                           const PointEdgePair& pair, const SelfContactParams& params) {
  const int i = boundary.nodes[pair.node];
  const auto& e = boundary.edges[pair.edge];
  const bool same_body = boundary.node_body[pair.node] == boundary.edge_body[pair.edge];
  const double rest_distance =
      same_body ? std::sqrt(point_edge_distance_squared(rest[i], rest[e[0]], rest[e[1]])) : 0.0;
  return squared_distance_barrier(pair_dhat(params.dhat, rest_distance, same_body), params.kappa,
                                  boundary.node_area[pair.node]);
}

void PairSumScratch::reserve(size_t pairs) {
  if (values.size() < pairs) {
    values.resize(pairs);
    active.resize(pairs);
    gradients.resize(pairs);
    blocks.resize(pairs);
  }
}

namespace {

// Pairs per block of the concurrent sums (~20-50 us of work at n_seg 256).
constexpr int kEnergyPairBlock = 1024;
constexpr int kDerivativePairBlock = 256;

// Runs fn(k) for every pair k, over the threads in fixed blocks of `block` pairs.
template <class Fn>
void for_each_pair(size_t pairs, int block, Fn&& fn) {
  const int n = static_cast<int>(pairs);
  const BlockSplit split = split_blocks(n, block, kMaxBlocks);
  run_blocks(split.blocks, [&](int b) {
    for (int k = split.begin(b); k < split.end(b, n); ++k) fn(k);
  });
}

// On one thread the serial loop (the same bits, without the slots' extra traffic).
bool runs_in_blocks(const PairSumScratch* scratch, size_t pairs, int block) {
  return scratch != nullptr && pairs >= 2 * static_cast<size_t>(block) && thread_count() > 1;
}

}  // namespace

double self_contact_energy(const Boundary& boundary, const std::vector<Vec2>& rest,
                           std::span<const PointEdgePair> pairs, const VecX& x,
                           const SelfContactParams& params, PairSumScratch* scratch) {
  const double dhat2 = params.dhat * params.dhat;
  const auto pair_value = [&](const PointEdgePair& pair) {
    const PairPoints q = pair_points(boundary, pair, x);
    const double d2 = point_edge_distance_squared(q.p, q.a, q.b);
    return d2 >= dhat2 ? 0.0 : barrier_value(d2, pair_barrier(boundary, rest, pair, params));
  };
  // Adding a pair's 0 changes no bit of the sum (it is never -0: every barrier is >= 0).
  double energy = 0.0;
  if (!runs_in_blocks(scratch, pairs.size(), kEnergyPairBlock)) {
    for (const PointEdgePair& pair : pairs) energy += pair_value(pair);
    return energy;
  }
  scratch->reserve(pairs.size());
  for_each_pair(pairs.size(), kEnergyPairBlock,
                [&](int k) { scratch->values[k] = pair_value(pairs[k]); });
  for (size_t k = 0; k < pairs.size(); ++k) energy += scratch->values[k];
  return energy;
}

void add_self_contact_gradient_hessian(const Boundary& boundary, const std::vector<Vec2>& rest,
                                       std::span<const PointEdgePair> pairs, const VecX& x,
                                       const SelfContactParams& params, double scale,
                                       VecX& gradient, std::vector<PointEdgeHessian>& hessians,
                                       PairSumScratch* scratch) {
  const double dhat2 = params.dhat * params.dhat;
  // One pair's gradient and scale * its projected Hessian; false when it is inactive.
  const auto pair_terms = [&](const PointEdgePair& pair, Vec6& g, PointEdgeHessian& h) {
    const PairPoints q = pair_points(boundary, pair, x);
    const double d2 = point_edge_distance_squared(q.p, q.a, q.b);
    if (d2 >= dhat2) return false;
    const BarrierParams barrier = pair_barrier(boundary, rest, pair, params);
    if (d2 >= barrier.dhat) return false;  // beyond this pair's own dhat
    g = point_edge_barrier_gradient(q.p, q.a, q.b, barrier);
    h = {q.nodes, scale * point_edge_barrier_hessian(q.p, q.a, q.b, barrier, true)};
    return true;
  };
  const auto add = [&](const Vec6& g, const PointEdgeHessian& h) {
    for (int k = 0; k < 3; ++k) gradient.segment<2>(2 * h.nodes[k]) += scale * g.segment<2>(2 * k);
    hessians.push_back(h);
  };
  if (!runs_in_blocks(scratch, pairs.size(), kDerivativePairBlock)) {
    Vec6 g;
    PointEdgeHessian h;
    for (const PointEdgePair& pair : pairs)
      if (pair_terms(pair, g, h)) add(g, h);
    return;
  }
  scratch->reserve(pairs.size());
  for_each_pair(pairs.size(), kDerivativePairBlock, [&](int k) {
    scratch->active[k] = pair_terms(pairs[k], scratch->gradients[k], scratch->blocks[k]);
  });
  for (size_t k = 0; k < pairs.size(); ++k)
    if (scratch->active[k]) add(scratch->gradients[k], scratch->blocks[k]);
}

}  // namespace invfree
