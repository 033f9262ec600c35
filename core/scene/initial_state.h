// The state a scene starts from: the square mesh's rest positions, optionally jittered
// by a deterministic pseudo-random displacement (SplitMix64, identical on every platform),
// and the initial velocity. `check_initial_state` rejects a start that the solver could
// not step from: a rest triangle whose area is not a normal double, an inverted triangle
// under a model that needs det F > 0, or a node on or through the ground or the ceiling.
// `check_mesh_fits_in_memory` refuses an n_seg whose simulation would need more than 80%
// of this machine's physical memory.
#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace invfree {

// mesh: scene_mesh(scene). Positions: rest, stretched, jittered by each body's edge
// length (except the fixed nodes' held coordinates); velocities: each body's.
VecX initial_positions(const SceneDef& scene, const Mesh& mesh);
VecX initial_velocities(const SceneDef& scene, const Mesh& mesh);
std::optional<SceneProblem> check_initial_state(const SceneDef& scene);

// Bytes a simulation of an n_seg mesh needs, an upper estimate: the measured peak of
// `invfree simulate` is about 2.8 kB per node at n_seg 128 and 256 (mostly the sparse
// factor, whose fill grows like log N); this allows 1 kB * (1 + log2(N) / 4) per node,
// about twice that.
double estimated_memory_bytes(int n_seg);
double estimated_memory_bytes_of_nodes(double nodes);  // any mesh's, by the same measure
// "" or a reason (with both figures) when the estimate exceeds 80% of physical memory.
std::string check_mesh_fits_in_memory(int n_seg);
std::string check_nodes_fit_in_memory(double nodes);
// The same for every body of a scene together.
std::string check_mesh_fits_in_memory(const SceneDef& scene);

}  // namespace invfree
