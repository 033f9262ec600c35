// A body's shape as a scene gives it ([mesh] or [[body]]): today's square grid, a
// rectangle, disk or ring, a polygon with holes, an SVG outline or a triangle mesh file.
// The core never reads a file: scene_io loads `file` into `loaded` (SVG paths flattened,
// scaled to metres, y up, the drawing's bounding-box centre at the origin; a mesh file's
// nodes and triangles as given) before the scene reaches the core. Every shape but the
// square is meshed by shape/shape_mesh.h (CGAL's constrained Delaunay mesher).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "enum_names.h"
#include "types.h"

namespace invfree {

// Points: particles only, no triangles (the course's chapter 0: free fall, a spring).
enum class ShapeKind { Square, Rectangle, Disk, Ring, Polygon, Svg, MeshFile, Points };
inline constexpr EnumName<ShapeKind> kShapeKindNames[] = {
    {ShapeKind::Square, "square"}, {ShapeKind::Rectangle, "rectangle"}, {ShapeKind::Disk, "disk"},
    {ShapeKind::Ring, "ring"},     {ShapeKind::Polygon, "polygon"},     {ShapeKind::Svg, "svg"},
    {ShapeKind::MeshFile, "mesh"}, {ShapeKind::Points, "points"}};

// Which regions of a set of closed paths are inside (SVG's fill-rule).
enum class FillRule { NonZero, EvenOdd };
inline constexpr EnumName<FillRule> kFillRuleNames[] = {{FillRule::NonZero, "nonzero"},
                                                        {FillRule::EvenOdd, "evenodd"}};

// A closed polygon, its last point joined to its first (not repeated), either orientation.
using Loop = std::vector<Vec2>;

// What scene_io read from ShapeDef::file.
struct ShapeFile {
  // svg: the closed paths, flattened, in metres, y up, centred; and the fill rule.
  std::vector<Loop> loops;
  FillRule fill_rule = FillRule::NonZero;
  // mesh: nodes (metres) and triangles (node indices) exactly as the file gives them.
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3>> triangles;
  bool operator==(const ShapeFile&) const = default;
};

struct ShapeDef {
  ShapeKind kind = ShapeKind::Square;  // the square's side and n_seg stay SceneDef's / BodyDef's
  double width = 2.0, height = 1.0;    // rectangle
  double radius = 0.5, inner_radius = 0.25;  // disk (radius), ring (both)
  Loop outline;                              // polygon
  std::vector<Loop> holes;                   // polygon
  std::vector<Vec2> points;                  // points: the particles' rest positions
  std::string file;       // svg, mesh: as the scene gives it (relative to the scene file)
  std::string path_id;    // svg: the one path to use ("": every closed path of the drawing)
  double scale = 0.01;    // svg: metres per SVG user unit
  double max_edge = 0.0;  // target edge length (m); 0: auto, the longer side of the
                          // shape's bounding box / n_seg (shape/shape_mesh.h)
  ShapeFile loaded;       // svg, mesh: filled by scene_io from `file`
  bool operator==(const ShapeDef&) const = default;
};

const char* shape_kind_name(ShapeKind k);
std::optional<ShapeKind> shape_kind_from_name(std::string_view name);

}  // namespace invfree
