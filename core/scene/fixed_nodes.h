// Fixed nodes (Dirichlet boundary conditions) chosen by rules in rest space, so that the
// same rule holds the same places at any n_seg: the named corners of the bounding box of
// all rest nodes (e.g. "top": top-left and top-right, the tutorial's 2_dirichlet), and
// every node whose rest position lies in [box_min, box_max] or in one of `boxes`. The solver
// eliminates their degrees of freedom (potential/fixed_dofs.h); they keep their initial positions.
// Inputs: the scene's [fixed] rule and the mesh. Output: node indices, ascending.
#pragma once

#include <optional>
#include <vector>

#include "scene/scene.h"

namespace invfree {

// The nodes the rule selects; empty when the scene has no [fixed] section.
std::vector<int> select_fixed_nodes(const SceneDef& scene, const Mesh& mesh);

// Why the rule is unusable, if it is: a non-empty box that holds no rest node, or a
// [fixed] section whose rules select no node at all.
std::optional<SceneProblem> fixed_rule_problem(const SceneDef& scene, const Mesh& mesh);

}  // namespace invfree
