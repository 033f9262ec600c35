// The mesh of a scene: every body's square (scene/mesh.h) or meshed shape placed at its offset and
// concatenated, body after body, with per-node masses and plane-contact areas.
// Inputs: a scene (its [mesh] and [[body]] tables). Outputs: one Mesh whose body_begin
// lists each body's first node (and body_triangle_begin its first triangle); node masses
// per body (MassMode within each body, so a body's mass is density x its area whatever
// the other bodies are); each node's contact area for the plane barriers: the side / n_seg
// of a square body (the demo's contact_area), half the rest lengths of a meshed shape's
// boundary node's two boundary edges (0 inside it); empty when every body is a square with
// the same one (the scene's contact_area() then serves every node).
#pragma once

#include <vector>

#include "scene/mesh.h"
#include "scene/scene.h"

namespace invfree {

Mesh scene_mesh(const SceneDef& scene);
// One body's mesh in its own frame: the square grid, or its shape meshed (shape/shape_mesh.h).
Mesh body_mesh(const PlacedBody& body);
// Every body is a [mesh] square grid (the case every scene before shapes was).
bool scene_has_only_squares(const SceneDef& scene);
// Each node's mass: [mesh] node_mass when > 0, else from density and `mass`.
std::vector<double> scene_node_masses(const SceneDef& scene, const Mesh& mesh);
std::vector<double> scene_node_contact_areas(const SceneDef& scene, const Mesh& mesh);
// Per triangle, the Lame parameters of its body; empty when every body uses the scene's
// [material] (the usual case: elasticity then reads one Lame for all).
std::vector<Lame> scene_triangle_lame(const SceneDef& scene, const Mesh& mesh);
// The body a node belongs to (body_begin is ascending).
int body_of_node(const Mesh& mesh, int node);

}  // namespace invfree
