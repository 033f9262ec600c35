// An SVG drawing's closed outlines as polygons (issue 27's `shape = "svg"`): the <path>,
// <polygon>, <polyline>, <rect>, <circle> and <ellipse> elements (every one outside <defs>,
// <clipPath>, <mask>, <symbol>, <pattern> and <marker>, or the one element, or group, whose
// id is path_id), with their own and their groups' `transform`s composed, curves and arcs
// flattened to a stated tolerance, then scaled to metres with y up and centred. The XML is
// read by pugixml; the path data, transforms and flattening are ours, so the flattening
// error has a proof (Wang's bound for Bézier curves, the sagitta for arcs).
#pragma once

#include <string>
#include <string_view>

#include "shape/shape.h"

namespace invfree {

// The flattening tolerance, relative: every point of a flattened curve or arc lies within
// kSvgFlatteningTolerance × D of the true curve, D the diagonal of the bounding box of the
// used elements' points and control points (an arc: its whole ellipse; in SVG user units
// after the transforms, before `scale`). In metres the bound is that times `scale`.
inline constexpr double kSvgFlatteningTolerance = 2.5e-4;

// Parses SVG text into out.loops (metres: x = scale·x_svg, y = −scale·y_svg, then moved so
// that the bounding box of the loops is centred on the origin; each loop's closing point
// not repeated, consecutive points closer than 1e-9 × D merged) and out.fill_rule (the
// elements' `fill-rule` attribute or style property, inherited from groups, nonzero by
// default; elements that disagree are an error). Only closed subpaths are kept: those
// ending in Z/z and those whose last point is within 1e-9 × D of their first. `name` is the
// file's name in errors. Returns "" or a one-line error, e.g.
// "bunny.svg has no closed path" or "bunny.svg:12: <path>: d: expected a number at 'x'".
std::string parse_svg_outline(std::string_view text, const std::string& name,
                              const std::string& path_id, double scale, ShapeFile& out);

}  // namespace invfree
