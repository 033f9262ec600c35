// A scene's boundary loads ([traction] / [[traction]], scene.h's TractionDef) turned into
// what the potential's load terms use: each table's boundary edges (both nodes at rest in
// its box, the same rule and tolerance as [fixed]'s boxes), the dead loads as one force per
// node (a table's total force spread over its edges by rest length, half of an edge's
// share to each of its nodes), and the pressure edges (each in the boundary's orientation,
// body on the left, so that pressure times the enclosed signed area is the potential).
// Inputs: the scene, its mesh and boundary. Outputs: plain arrays (potential/boundary_load.h).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "scene/boundary.h"
#include "scene/scene.h"

namespace invfree {

struct PressureEdge {
  int a = 0, b = 0;  // boundary edge a -> b, the body on its left
  double pressure = 0.0;
};

// Indices into boundary.edges of the edges whose two nodes lie in the traction's box.
std::vector<int> traction_edges(const TractionDef& t, const Mesh& mesh, const Boundary& boundary);
// 2N: the dead loads' force on each node (N per unit thickness); empty when no table has one.
VecX traction_node_forces(const SceneDef& s, const Mesh& mesh, const Boundary& boundary);
// Every table's pressure edges; empty when no table has a pressure.
std::vector<PressureEdge> pressure_edges(const SceneDef& s, const Mesh& mesh,
                                         const Boundary& boundary);
// Why a table is unusable: a force or pressure that is not finite, an empty box or one
// that selects no boundary edge, a pressure on edges that are not whole boundary loops.
std::optional<SceneProblem> traction_problem(const SceneDef& s, const Mesh& mesh);

}  // namespace invfree
