#include "scene/boundary.h"

#include <algorithm>
#include <cassert>

namespace invfree {

namespace {

// One triangle's edge: the unordered key (lo, hi) and the direction with the triangle on
// the left (a -> b).
struct TriangleEdge {
  int lo, hi, a, b;
};

int body_of(std::span<const int> body_begin, int node) {
  return static_cast<int>(std::upper_bound(body_begin.begin(), body_begin.end(), node) -
                          body_begin.begin()) -
         1;
}

}  // namespace

Boundary find_boundary(const Mesh& mesh, std::span<const int> body_begin) {
  assert(!body_begin.empty() && body_begin[0] == 0);
  assert(std::is_sorted(body_begin.begin(), body_begin.end()));
  std::vector<TriangleEdge> all;
  all.reserve(3 * mesh.triangles.size());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles[t];
    const bool clockwise = mesh.rest_area[t] < 0.0;
    for (int k = 0; k < 3; ++k) {
      int a = tri[k], b = tri[(k + 1) % 3];
      if (clockwise) std::swap(a, b);
      all.push_back({std::min(a, b), std::max(a, b), a, b});
    }
  }
  std::sort(all.begin(), all.end(), [](const TriangleEdge& l, const TriangleEdge& r) {
    return l.lo != r.lo ? l.lo < r.lo : l.hi < r.hi;
  });

  Boundary out;
  for (size_t k = 0; k < all.size();) {
    size_t end = k + 1;
    while (end < all.size() && all[end].lo == all[k].lo && all[end].hi == all[k].hi) ++end;
    if (end == k + 1) out.edges.push_back({all[k].a, all[k].b});
    k = end;
  }
  std::sort(out.edges.begin(), out.edges.end());

  constexpr int kOnBoundary = -2;  // marked, slot not yet given
  out.node_slot.assign(mesh.rest.size(), -1);
  for (const auto& e : out.edges)
    for (int v : e) out.node_slot[v] = kOnBoundary;
  for (int v = 0; v < mesh.node_count(); ++v)
    if (out.node_slot[v] == kOnBoundary) {
      out.node_slot[v] = out.node_count();
      out.nodes.push_back(v);
      out.node_body.push_back(body_of(body_begin, v));
    }
  out.node_area.assign(out.nodes.size(), 0.0);
  for (const auto& e : out.edges) {
    const double half = 0.5 * (mesh.rest[e[1]] - mesh.rest[e[0]]).norm();
    out.node_area[out.node_slot[e[0]]] += half;
    out.node_area[out.node_slot[e[1]]] += half;
    out.edge_body.push_back(body_of(body_begin, e[0]));
  }
  return out;
}

}  // namespace invfree
