// The vertex lists of one frame, built on the CPU from a FrameState: the world (the
// planes' hatched bands and fills, the triangles coloured by det F or another field, the
// mesh edges, the body's outline, the planes' surfaces, the inverted triangles' rings, the
// stress glyphs, the overlays' strokes and dots, the selected triangle's outline) and the side
// panel (words, numbers and the colour bar), in the frame's pixels (x right, y down). renderer.cpp
// uploads and draws them; the layout of a frame is camera.h's, its words frame_text.h's.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/colormap.h"
#include "app/render/camera.h"
#include "app/render/renderer.h"
#include "app/render/text_atlas.h"

namespace invfree::render {

struct Rgba {
  float r, g, b, a;
};
constexpr Rgba rgba(Rgb c, float a = 1.0f) {
  return {c.r, c.g, c.b, a};
}

// Colours the GL passes use (the rest of the palette is in frame_vertices.cpp).
constexpr Rgba kPlotBackground{0.955f, 0.96f, 0.968f, 1.0f};  // so that white (det F = 1) shows
constexpr Rgba kPlaneHatch{0.60f, 0.60f, 0.60f, 1.0f};

enum FontSize { kTitle = 0, kBody = 1, kSmall = 2 };

struct ShapeVertex {
  float x, y;
  Rgba c;
  float across = 0.0f, half_width = 0.0f;  // stroke antialiasing (shape_vertex.glsl)
};
struct TextVertex {
  float x, y, u, v;
  Rgba c;
};

using Shapes = std::vector<ShapeVertex>;

// Where each layer of a frame lies in FrameVertices::shapes: [0, world_fills) the world's opaque
// fills, [world_fills, world_end) its strokes, [world_end, panel_backdrop) the panel's
// opaque backdrop, [panel_backdrop, end) the panel's content.
struct ShapeRanges {
  size_t world_fills = 0, world_end = 0, panel_backdrop = 0;
};

// The lists of a frame and what building them needs and keeps between frames.
struct FrameVertices {
  Shapes shapes;   // fills and strokes, in the order of ShapeRanges
  Shapes hatched;  // the planes' surface bands, drawn with the hatch pattern
  std::vector<TextVertex> text;
  std::vector<std::string> words;  // every string add_text drew, in order (tests read them)
  // The text's font: the atlas built at font_sizes (indexed by FontSize).
  const TextAtlas* atlas = nullptr;
  std::vector<double> font_sizes;
  // Scratch, and the mesh's edges with the triangles they were found from: the sort of
  // every edge is redone only when the mesh changes, not every frame.
  std::vector<GlyphQuad> glyphs;
  std::vector<std::pair<int, int>> interior_edges, boundary_edges;
  std::vector<std::array<int, 3>> edges_of;
  // The stress glyphs' scratch: centroids, the triangles drawn, and per thinning cell the
  // triangle nearest its middle and that distance.
  std::vector<Vec2> glyph_centroids;
  std::vector<int> glyph_chosen, glyph_cell_best;
  std::vector<double> glyph_cell_distance;

  // Appends the quads of `s` at size index `size` with its baseline at (x, baseline);
  // `align` 0: left, 0.5: centred, 1: right.
  void add_text(std::string_view s, int size, double x, double baseline, Rgba color,
                double align = 0.0);
};

// Stress glyphs need this many pixels (at 1280x720; scaled with the frame, at least 16) per
// glyph to be read as a cross: a mesh whose mean triangle is smaller gets one glyph per
// cell of that size instead of one per triangle.
constexpr double kGlyphCellPixels = 28.0;
inline double glyph_cell_pixels(double layout_scale) {
  return std::max(16.0, std::round(kGlyphCellPixels * layout_scale));
}

// Replaces v's lists with those of `state` seen through `cam` in layout L (the mesh's
// interior edges, the panel, the colour range and the rings of inverted triangles as
// `options` say). Returns where each layer lies.
ShapeRanges build_frame_vertices(FrameVertices& v, const FrameState& state, const FrameLayout& L,
                                 const Camera& cam, const DrawOptions& options);

}  // namespace invfree::render
