// Triangle-mesh files (issue 27's `shape = "mesh"`): gmsh's .msh, ASCII version 2 (2.x) or
// 4.1, and Wavefront .obj, read into nodes and triangles exactly as the file gives them
// (coordinates in metres, node tags mapped to 0-based indices in the order the nodes appear).
// Only parsing: whether the triangles are inverted, degenerate, duplicated or leave nodes
// unused is the core's check (shape/mesh_check.h).
#pragma once

#include <string>
#include <string_view>

#include "shape/shape.h"

namespace invfree {

// gmsh .msh: $MeshFormat 2.x or 4.1 with file type 0 (ASCII; binary is refused), $Nodes and
// $Elements; other sections ($Entities, $PhysicalNames, ...) are skipped. Elements: 3-node
// triangles (type 2) are kept, points and lines (types 15, 1, 8, 26, 27, 28) ignored, every
// other type refused. Every node's z must be 0 within 1e-12 × the nodes' bounding-box diagonal.
// Fills out.nodes and out.triangles; returns "" or one line "<name>:<line>: <reason>".
std::string parse_msh(std::string_view text, const std::string& name, ShapeFile& out);

// Wavefront .obj: `v x y z` (z = 0 within 1e-12 × the size, as above) and `f` with three
// vertices (`1`, `1/2`, `1/2/3`, `1//3`; negative indices count back from the last vertex so
// far); faces of four or more vertices are refused; vt, vn, o, g, s, l, usemtl, mtllib and
// comments are ignored. Same output and errors as parse_msh.
std::string parse_obj(std::string_view text, const std::string& name, ShapeFile& out);

}  // namespace invfree
