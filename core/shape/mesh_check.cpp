// Mesh file validation (mesh_check.h): the checks in the header's order, the edge checks
// on a sorted list of (edge, triangle) entries so the cost is O(m log m).
#include "shape/mesh_check.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "collision/orientation.h"

namespace invfree {
namespace {

std::string tri(std::size_t t) {
  return "triangle " + std::to_string(t);
}

}  // namespace

CheckedMesh check_mesh(const ShapeFile& file) {
  CheckedMesh out;
  const auto& nodes = file.nodes;
  const auto& tris = file.triangles;
  const int n = static_cast<int>(nodes.size());
  auto fail = [&](std::string reason) {
    out.error = "file: " + std::move(reason);
    return out;
  };
  if (tris.empty()) return fail("no triangle");
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int v : tris[t])
      if (v < 0 || v >= n)
        return fail(tri(t) + " refers to node " + std::to_string(v) + ", but there are " +
                    std::to_string(n) + " nodes");
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(nodes[i].x()) || !std::isfinite(nodes[i].y()))
      return fail("node " + std::to_string(i) + " is not finite");
  Eigen::AlignedBox2d box;
  for (const Vec2& p : nodes) box.extend(p);
  const double size = box.sizes().maxCoeff();
  std::vector<int> orient(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const auto& [a, b, c] = tris[t];
    if (a == b || b == c || a == c) return fail(tri(t) + " is degenerate (a node repeated)");
    const Vec2 u = nodes[b] - nodes[a], v = nodes[c] - nodes[a];
    orient[t] = orientation(nodes[a], nodes[b], nodes[c]);
    if (orient[t] == 0 || std::abs(u.x() * v.y() - u.y() * v.x()) <= kDegenerateArea * size * size)
      return fail(tri(t) + " is degenerate (zero area)");
  }
  // Duplicates: the sorted node sets, equal neighbours after sorting.
  std::vector<std::pair<std::array<int, 3>, int>> sets(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) {
    sets[t] = {tris[t], static_cast<int>(t)};
    std::sort(sets[t].first.begin(), sets[t].first.end());
  }
  std::sort(sets.begin(), sets.end());
  std::pair<int, int> dup{-1, -1};
  for (std::size_t k = 1; k < sets.size(); ++k)
    if (sets[k].first == sets[k - 1].first) {
      const std::pair<int, int> d{sets[k - 1].second, sets[k].second};
      if (dup.first < 0 || d < dup) dup = d;
    }
  if (dup.first >= 0)
    return fail("triangles " + std::to_string(dup.first) + " and " + std::to_string(dup.second) +
                " are duplicates (the same three nodes)");
  std::vector<char> used(n, 0);
  for (const auto& t : tris)
    for (int v : t) used[v] = 1;
  for (int i = 0; i < n; ++i)
    if (!used[i]) return fail("node " + std::to_string(i) + " is used by no triangle");
  // Orientation: the majority (the first triangle's on a tie); the first one against it.
  const long ccw = std::count(orient.begin(), orient.end(), 1);
  const long cw = static_cast<long>(tris.size()) - ccw;
  const int majority = ccw > cw ? 1 : cw > ccw ? -1 : orient[0];
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (orient[t] != majority)
      return fail(tri(t) + (majority > 0 ? " is inverted (clockwise where the others are "
                                           "counter-clockwise)"
                                         : " is inverted (counter-clockwise where the others "
                                           "are clockwise)"));
  out.nodes = nodes;
  out.triangles = tris;
  if (majority < 0) {
    out.flipped = true;
    for (auto& t : out.triangles) std::swap(t[1], t[2]);
  }
  // Edges, now all counter-clockwise: (low, high, direction, triangle).
  std::vector<std::tuple<int, int, int, int>> edges;
  edges.reserve(3 * tris.size());
  for (std::size_t t = 0; t < out.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = out.triangles[t][i], b = out.triangles[t][(i + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b), a < b ? 0 : 1, static_cast<int>(t));
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k < edges.size();) {
    std::size_t end = k;
    while (end < edges.size() && std::get<0>(edges[end]) == std::get<0>(edges[k]) &&
           std::get<1>(edges[end]) == std::get<1>(edges[k]))
      ++end;
    const std::string edge = "edge " + std::to_string(std::get<0>(edges[k])) + "-" +
                             std::to_string(std::get<1>(edges[k]));
    if (end - k > 2) {
      out = CheckedMesh{};
      return fail(edge + " is shared by more than two triangles (non-manifold)");
    }
    if (end - k == 2 && std::get<2>(edges[k]) == std::get<2>(edges[k + 1])) {
      const int t0 = std::get<3>(edges[k]), t1 = std::get<3>(edges[k + 1]);
      out = CheckedMesh{};
      return fail("triangles " + std::to_string(t0) + " and " + std::to_string(t1) +
                  " overlap (both on the same side of " + edge + ")");
    }
    k = end;
  }
  return out;
}

}  // namespace invfree
