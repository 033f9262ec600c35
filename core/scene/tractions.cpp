#include "scene/tractions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "scene/fixed_nodes.h"

namespace invfree {

namespace {

std::string which_table(const SceneDef& s, size_t k) {
  return s.tractions.size() > 1 ? " (in [[traction]] " + std::to_string(k + 1) + ")" : "";
}

// Every node of the edges has as many selected edges leaving it as arriving: the edges are
// whole boundary loops (the loops are simple, so this is exact).
bool whole_loops(const std::vector<int>& edges, const Boundary& boundary) {
  std::map<int, int> balance;
  for (int e : edges) {
    ++balance[boundary.edges[e][0]];
    --balance[boundary.edges[e][1]];
  }
  return std::all_of(balance.begin(), balance.end(), [](const auto& kv) { return kv.second == 0; });
}

}  // namespace

std::vector<int> traction_edges(const TractionDef& t, const Mesh& mesh, const Boundary& boundary) {
  std::vector<int> out;
  if ((t.box_min.array() > t.box_max.array()).any() || mesh.rest.empty()) return out;
  const double tol = rest_box_tolerance(mesh);
  for (int e = 0; e < boundary.edge_count(); ++e)
    if (in_rest_box(t.box_min, t.box_max, mesh.rest[boundary.edges[e][0]], tol) &&
        in_rest_box(t.box_min, t.box_max, mesh.rest[boundary.edges[e][1]], tol))
      out.push_back(e);
  return out;
}

VecX traction_node_forces(const SceneDef& s, const Mesh& mesh, const Boundary& boundary) {
  VecX f;
  for (const TractionDef& t : s.tractions) {
    if (t.force == Vec2::Zero()) continue;
    if (f.size() == 0) f = VecX::Zero(2 * mesh.node_count());
    const std::vector<int> edges = traction_edges(t, mesh, boundary);
    double total = 0.0;
    for (int e : edges)
      total += (mesh.rest[boundary.edges[e][1]] - mesh.rest[boundary.edges[e][0]]).norm();
    if (!(total > 0.0)) continue;
    for (int e : edges) {
      const auto& [a, b] = boundary.edges[e];
      const Vec2 share = t.force * (0.5 * (mesh.rest[b] - mesh.rest[a]).norm() / total);
      f.segment<2>(2 * a) += share;
      f.segment<2>(2 * b) += share;
    }
  }
  return f;
}

std::vector<PressureEdge> pressure_edges(const SceneDef& s, const Mesh& mesh,
                                         const Boundary& boundary) {
  std::vector<PressureEdge> out;
  for (const TractionDef& t : s.tractions) {
    if (t.pressure == 0.0) continue;
    for (int e : traction_edges(t, mesh, boundary))
      out.push_back({boundary.edges[e][0], boundary.edges[e][1], t.pressure});
  }
  return out;
}

std::optional<SceneProblem> traction_problem(const SceneDef& s, const Mesh& mesh) {
  if (s.tractions.empty()) return std::nullopt;
  if (s.tractions.size() > static_cast<size_t>(kMaxTractions))
    return SceneProblem{
        "traction.force", "at most " + std::to_string(kMaxTractions) + " [[traction]] tables", {}};
  for (size_t k = 0; k < s.tractions.size(); ++k) {
    const TractionDef& t = s.tractions[k];
    const std::string in = which_table(s, k);
    if (!t.force.allFinite()) return SceneProblem{"traction.force", "must be finite" + in, {}};
    if (!std::isfinite(t.pressure))
      return SceneProblem{"traction.pressure", "must be finite" + in, {}};
    if (!t.box_min.allFinite() || !t.box_max.allFinite())
      return SceneProblem{"traction.box_min", "the box must be finite" + in, {"traction.box_max"}};
    if ((t.box_min.array() > t.box_max.array()).any())
      return SceneProblem{"traction.box_min",
                          "the box's min corner is above or right of its max" + in,
                          {"traction.box_max"}};
  }
  const Boundary boundary = find_boundary(mesh);
  for (size_t k = 0; k < s.tractions.size(); ++k) {
    const TractionDef& t = s.tractions[k];
    const std::vector<int> edges = traction_edges(t, mesh, boundary);
    if (edges.empty()) {
      char buf[240];
      std::snprintf(buf, sizeof buf,
                    "the box [%g, %g] x [%g, %g] holds no boundary edge of the rest mesh "
                    "(both of an edge's nodes must lie in it)",
                    t.box_min.x(), t.box_max.x(), t.box_min.y(), t.box_max.y());
      return SceneProblem{"traction.box_min",
                          buf + which_table(s, k),
                          {"traction.box_max", "mesh.side", "mesh.shape"}};
    }
    if (t.pressure != 0.0 && !whole_loops(edges, boundary))
      return SceneProblem{"traction.pressure",
                          "its box selects part of a boundary loop; a follower pressure is "
                          "conservative only on whole loops (select a whole loop, or use "
                          "`force` for a dead load)" +
                              which_table(s, k),
                          {"traction.box_min", "traction.box_max"}};
  }
  return std::nullopt;
}

}  // namespace invfree
