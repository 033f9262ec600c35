// The entry point that turns a body's shape (shape/shape.h) into its rest mesh: every
// kind but the square. Rectangle, disk, ring, polygon and svg are validated
// (shape/shape_region.h), refused when the mesh would be too large, and meshed by CGAL's
// constrained Delaunay mesher (shape/triangulate.h); a mesh file is validated
// (shape/mesh_check.h) and used as given (flipped to counter-clockwise when all its
// triangles are clockwise). Never throws; deterministic bit for bit; thread-safe.
#pragma once

#include <string>

#include "scene/mesh.h"
#include "shape/shape.h"

namespace invfree {

struct ShapeMeshResult {
  Mesh mesh;
  // "key: reason" with the key relative to the shape's table ("outline", "holes[1]",
  // "max_edge", "file", "radius"); "" on success.
  std::string error;
};

// Every triangle's smallest angle is >= kMinAngleDegrees, except near an input corner
// sharper than 60 degrees, where Delaunay refinement cannot improve the angles the input
// forces (CGAL's clusters leave those triangles alone so that refinement ends). CGAL's
// shape bound B = sin^2(smallest angle) is 0.125 (shape/triangulate.h), i.e. 20.705
// degrees, the bound under which Ruppert's refinement is proven to end; 20.7 is that,
// rounded down. Small input features cost triangles (refinement grades down to them),
// not angles.
constexpr double kMinAngleDegrees = 20.7;

// The largest mesh mesh_shape builds. Refused before meshing when the estimate
//   kTriangleEstimateFactor * area / (sqrt(3)/4 max_edge^2)
// passes it. CGAL's triangles under a size bound max_edge are smaller than equilateral
// ones of side max_edge: 2.17 times as many on the rectangle, disk, ring and plate with
// holes of tests/shape/ (6,000 to 25,000 triangles, within 1% of each other), so the
// estimate is within a few percent for shapes several max_edge wide. 2,000,000 triangles
// mesh in about 10 s and are far beyond what steps interactively; the default max_edge
// (the bounding box / n_seg) gives a few thousand. Thin shapes, whose width rather than
// max_edge sets the triangles' size, are held by the refinement step budget instead (an
// error naming the step count, never a hang).
constexpr long kMaxShapeTriangles = 2'000'000;
constexpr double kTriangleEstimateFactor = 2.2;

// The shape meshed at rest in the body's own frame (no offset), compute_rest_data done,
// triangles counter-clockwise. max_edge: the target edge length (shape_max_edge in
// shape/shape_region.h); every edge of a meshed shape is <= max_edge (a mesh file is
// taken as it is). The last few results are cached (validation and the simulation mesh
// the same shape): a repeated call returns a copy of the cached result.
ShapeMeshResult mesh_shape(const ShapeDef& shape, double max_edge);

// The triangle count mesh_shape estimates for its cap (NaN for a shape without area).
double estimated_triangle_count(const ShapeDef& shape, double max_edge);

}  // namespace invfree
