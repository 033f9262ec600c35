// A shape's region (shape/shape.h, every kind but the square and the mesh file) as the
// boundary loops the mesher constrains: each loop with its role after the fill rule,
// outer (the region is inside it) or hole (outside it), oriented outer counter-clockwise
// and holes clockwise, so that the region lies on the left of every loop.
//  - rectangle: width x height, centred at the origin, four corners.
//  - disk / ring: the circle(s) of radius (and inner_radius) about the origin as regular
//    polygons whose points lie on the circle, n = max(12, ceil(2 pi r / max_edge)) segments
//    rounded up to a multiple of 4 (a flat side at the bottom, mirror-symmetric about both
//    axes), so every chord is <= max_edge. Area error: a regular n-gon inscribed in
//    a circle of radius r has area (n/2) r^2 sin(2 pi / n), short of pi r^2 by a relative
//    1 - sin(x)/x <= x^2/6 with x = 2 pi / n (its sagitta, the gap between chord and arc,
//    is r (1 - cos(pi/n)) <= r (pi/n)^2 / 2); region_area_error_bound gives the sum over
//    the circles.
//  - polygon: outline and holes as given (either orientation), validated by
//    check_polygon_with_holes.
//  - svg: ShapeDef::loaded.loops under loaded.fill_rule. The loops must be pairwise
//    disjoint (validated; crossing or touching paths are an error, not resolved). Their
//    nesting tree gives each loop the winding number just inside it (the sum of its own
//    and its ancestors' orientations) and just outside (its parent's inside); a loop is
//    kept where the fill status changes across it (nonzero: w != 0; evenodd: w odd), as an
//    outer loop when its inside is filled.
// Errors are "key: reason" with the key relative to the shape's table ("radius: must be
// > 0", "holes[1]: not inside the outline", "file: paths[2] and paths[5] cross").
#pragma once

#include <string>
#include <vector>

#include "shape/shape.h"
#include "types.h"

namespace invfree {

struct RegionLoop {
  Loop points;  // outer: counter-clockwise; hole: clockwise
  bool hole = false;
};

struct ShapeRegion {
  std::vector<RegionLoop> loops;  // in the shape's order (outline, then holes; svg: file order)
  std::string error;              // "" when valid
};

// The region of `shape` meshed with target edge length `max_edge` (which sets the
// discretisation of disk and ring; must be > 0 for those). kind must not be Square or
// MeshFile (an error names the kind).
ShapeRegion shape_region(const ShapeDef& shape, double max_edge);

// The shape's keys alone (sizes positive and finite, radii ordered, loops valid), without
// building the region: "" or "key: reason". Meshes (MeshFile) are checked by
// shape/mesh_check.h, the square by the scene.
std::string validate_shape(const ShapeDef& shape);

// Upper bound on |area of shape_region(shape, max_edge) - shape_area(shape)|: 0 for
// polygons (rectangle, polygon, svg), the inscribed polygons' shortfall for disk and ring
// (see above).
double region_area_error_bound(const ShapeDef& shape, double max_edge);

// The number of segments a circle of radius r is cut into for max_edge.
int circle_segments(double r, double max_edge);

// The shape's rest bounding box in its own frame (no offset): rectangle, disk and ring
// about the origin, the polygon's outline, the svg's loops, the mesh file's nodes. Empty
// (isEmpty()) for the square, whose side is the scene's, and for a shape with no points.
Eigen::AlignedBox2d shape_bounds(const ShapeDef& shape);

// The target edge length: shape.max_edge when > 0, otherwise the longer side of
// shape_bounds / n_seg (the square's rule: n_seg segments along its side).
double shape_max_edge(const ShapeDef& shape, int n_seg);

// The exact area of the shape's region: w h, pi r^2 (not the inscribed polygon's),
// pi (r^2 - inner_radius^2), the polygon's outline less its holes, the svg's filled
// region, the mesh file's triangles. NaN for the square and for an invalid shape.
double shape_area(const ShapeDef& shape);

}  // namespace invfree
