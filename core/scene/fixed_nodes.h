// Fixed nodes (Dirichlet boundary conditions) chosen by rules in rest space, so that the
// same rule holds the same places at any n_seg: the named corners of the bounding box of
// all rest nodes (e.g. "top": top-left and top-right, the tutorial's 2_dirichlet), and
// every node whose rest position lies in [box_min, box_max] or in one of `boxes`; of each,
// both coordinates or (`components`, a roller support) only x or only y. The solver
// eliminates their degrees of freedom (potential/fixed_dofs.h); they keep their initial positions.
// Inputs: the scene's [fixed] rule and the mesh. Output: node indices, ascending.
#pragma once

#include <optional>
#include <vector>

#include "scene/scene.h"

namespace invfree {

// The rule of every rest-space box ([fixed]'s boxes, [traction]'s): a point is in [lo, hi]
// within rest_box_tolerance, 1e-9 of the rest mesh's size (rest positions are sums of
// multiples of side / n_seg: far below an edge, far above rounding).
double rest_box_tolerance(const Mesh& mesh);
bool in_rest_box(const Vec2& lo, const Vec2& hi, const Vec2& p, double tol);

// The nodes the rule selects; empty when the scene has no [fixed] section.
std::vector<int> select_fixed_nodes(const SceneDef& scene, const Mesh& mesh);

// The fixed nodes' held degrees of freedom (2 node + 0 for x, + 1 for y), ascending:
// both of each node's, or only x or only y under [fixed] components.
std::vector<int> select_fixed_dofs(const SceneDef& scene, const Mesh& mesh);

// A static scene (solver.integrator = "static") has a minimum only where every body is
// held against rigid motion: the held dofs of its nodes must block both translations and
// the rotation (a plane does not: it pushes only where the body touches it, and before
// contact the potential has no minimum). Why not, naming the body and the free motion;
// nullopt for a dynamic scene.
std::optional<SceneProblem> static_support_problem(const SceneDef& scene, const Mesh& mesh);

// Why the rule is unusable, if it is: a non-empty box that holds no rest node, or a
// [fixed] section whose rules select no node at all.
std::optional<SceneProblem> fixed_rule_problem(const SceneDef& scene, const Mesh& mesh);

}  // namespace invfree
