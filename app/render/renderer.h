// The renderer: draws one simulation state as a figure into its own framebuffer of a
// fixed size, the same way live (GLFW window) and offscreen (OSMesa), so both agree pixel
// for pixel on the same GL implementation.
//
// What a frame shows (layout in camera.h, words in frame_text.h):
//  - every triangle filled with the colour of FrameState::field: by default
//    det_f_color(det F) (app/colormap.h): blue compression, white at det F = 1, red
//    stretch, green det F <= 0; or Psi, the signed principal stress or the clamped count
//    on the scales of app/field_colormap.h;
//  - the triangle edges (DrawOptions::edges) and the body's outline;
//  - the ground and the ceiling as hatched half-planes;
//  - a side panel: scene name, model, mu, lambda, t, step, min/max det F (and the count of
//    inverted triangles when there are any), and the colour bar of the field the
//    triangles are coloured by, with numeric ticks, markers at the current min and max, and the det
//    F <= 0 swatch (a ring for the other fields: inverted triangles are ringed in every colouring);
//  - overlays (FrameState::overlays) over the world: points as dots and segments between
//    them as strokes, one colour each: a mesh without triangles' particles and springs
//    (the course's chapter 0), the affine basis's anchor triangle (chapter 9);
//  - optionally a cross of principal stress strokes per triangle (or per cell of a fine
//    mesh) and a thick outline around one selected triangle;
//  - a failed run's last frame (FrameState::failure): a red border around the world and
//    a red banner with the failure at its top.
// A frame with no triangles (particles only) says so on the panel in place of det F and
// has no colour bar.
// Nothing depends on the wall clock, so the same state gives the same picture.
//
// Antialiasing is analytic, so it is the same on every OpenGL implementation and costs
// no multisampling (which under llvmpipe costs more than the rest of the frame): strokes
// (mesh edges, the body's outline, the plane surfaces) get a one-pixel coverage ramp in
// the shader, the hatching is antialiased by distance, text is pixel-aligned
// stb_truetype coverage, and the fills' own edges lie under strokes. (create's
// max_samples can add multisampling on a hardware GL.)
//
// GL use: only through GlApi (gl_api.h). Needs a current OpenGL 3.3 context (core or
// compatibility profile) for create, draw, read_pixels and the destructor. draw
// binds its own framebuffer, program, vertex array and texture, and restores the draw and
// read framebuffer bindings and the viewport it found; it leaves no program, vertex array
// or texture bound and GL_BLEND, GL_SCISSOR_TEST and GL_MULTISAMPLE as it found them.
//
// Use:
//   auto r = Renderer::create(get_proc_address, 1280, 720, &error);
//   r->draw(capture_frame_state(sim));
//   r->read_pixels(&rgba);            // offscreen: RGBA8, bottom row first
//   DrawOptions live; live.framebuffer = 0;
//   r->draw(capture_frame_state(sim), live);   // live: straight into the window's back buffer
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/colormap.h"
#include "app/field_colormap.h"
#include "app/render/camera.h"
#include "app/render/gl_proc.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree::render {

// Points drawn over the world, above the triangles (and their edges, rings and glyphs),
// below the selected triangle's outline and the panel: every point a dot, every segment a
// stroke between two of the points (antialiased as the mesh's edges), all in one colour.
struct Overlay {
  std::vector<Vec2> points;                  // world metres
  std::vector<std::array<int, 2>> segments;  // indices into points
  Rgb color{0.0f, 0.0f, 1.0f};
  // The dots' radius in metres (so that they scale with the picture), drawn at least
  // kMinOverlayDotPixels (scaled with the frame) so that a coarse view still shows them;
  // 0: no dots.
  double dot_radius = 0.0;
  double stroke_width = 1.5;  // pixels at 1280x720, scaled with the frame (at least 1)
};
constexpr double kMinOverlayDotPixels = 2.5;

// The overlay colours: the tutorial's blue particles and springs, its red anchor triangle.
constexpr Rgb kParticleColor{0.05f, 0.22f, 0.85f};
constexpr Rgb kAnchorColor{0.86f, 0.06f, 0.06f};
// The bodies' paths (BodyPaths, view_choices.h): dark, apart from the det F colours.
constexpr Rgb kPathColors[] = {{0.30f, 0.05f, 0.45f}, {0.75f, 0.35f, 0.0f}, {0.0f, 0.40f, 0.30f}};

// What one frame shows, copied out of a Simulation (so a frame can be drawn while the
// simulation goes on, e.g. on another thread).
struct FrameState {
  SceneDef scene;
  VecX x;  // 2N node positions
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> body_begin{0};  // each body's first node (Mesh::body_begin)
  std::vector<double> det_f;       // per triangle
  // What the triangles are coloured by (core/triangle_fields.h) and its value per triangle
  // (det F: the same as det_f).
  TriangleField color_by = TriangleField::DetF;
  std::vector<double> field;
  // With stress glyphs asked for: each triangle's principal Cauchy stresses (larger
  // first, Pa) and the first one's unit direction; empty otherwise.
  std::vector<Vec2> principal_stress, principal_direction;
  // Drawn over the world in this order (see Overlay).
  std::vector<Overlay> overlays;
  double ceiling_y = 0.0;
  double time = 0.0;
  long step = 0;
  // Set when the run failed after this state (the last good one): "step 33 failed:
  // penetrated: ...". The frame is then marked in the picture (a red border and banner),
  // so a failed run's last frame does not look like a normal one.
  std::string failure;
};

// What a capture computes besides det F.
struct CaptureOptions {
  TriangleField color_by = TriangleField::DetF;
  bool stress_glyphs = false;  // fill principal_stress and principal_direction
};
// det_f: the state's det F per triangle when the caller has it already (else computed).
// The overlays: a mesh without triangles gets its nodes as dots and its springs as
// strokes (particle_overlay); the affine basis ([reduced] basis = "polynomial", order 1)
// its anchor triangle (anchor_overlay), when core gives one.
FrameState capture_frame_state(const Simulation& sim, const std::vector<double>* det_f = nullptr,
                               const CaptureOptions& capture = {});

// The particles and springs of a mesh without triangles: nodes x (2N) as dots of radius
// particle_dot_radius, the springs' node pairs as strokes.
Overlay particle_overlay(const VecX& x, const std::vector<std::array<int, 2>>& springs,
                         double dot_radius);
// The dots' radius for particles at rest positions `rest` joined by `springs`: a tenth of
// the median spring's rest length (the tutorial: 0.02 m at 0.25 m spacing), at most the
// tutorial's 0.1 m of a lone particle (also what a particle without springs gets).
double particle_dot_radius(const std::vector<Vec2>& rest,
                           const std::vector<std::array<int, 2>>& springs);
// The affine basis's anchor triangle: its three corners as red dots (a fifth of the mesh's
// spacing, twice the tutorial's, which at n_seg 10 is 3 pixels) joined by red strokes.
Overlay anchor_overlay(const std::array<Vec2, 3>& corners, double spacing);

struct DrawOptions {
  bool edges = true;  // triangle edges (the outline is always drawn)
  bool panel = true;  // the side panel (text, colour bar); false: the world fills the frame
  bool panel_overlay = false;  // with panel: drawn over the world, which fills the frame
  // The det F colour scale's range (colormap.h): 1/range..range; `color_range_auto` says on
  // the bar that it was chosen from the data (auto_det_f_range), not the fixed kDetFRange.
  double color_range = kDetFRange;
  bool color_range_auto = false;
  // The scale of the other fields (FrameState::color_by Psi, stress, clamped): unset, it is
  // chosen from the frame's own values (auto_field_scale in field_legend.h); a movie
  // passes the widest so far (ColorRangeTracker::apply_field) so its colours keep meaning.
  std::optional<FieldScale> field_scale;
  bool ring_inverted = true;  // a ring around every inverted triangle (det F <= 0)
  // The inspected triangle (the live inspector's, `inspect`'s): outlined, dark under
  // bright yellow, above everything else in the world; -1 (or out of range): none.
  int selected_triangle = -1;
  // A pair of short strokes per triangle along its principal stresses, length by
  // magnitude relative to the frame's largest, tension red, compression blue (needs a
  // state captured with CaptureOptions::stress_glyphs). Where triangles are smaller than
  // kGlyphCellPixels (frame_vertices.h) one glyph per cell of that size is drawn.
  bool stress_glyphs = false;
  // A heading across the world's top, on a light band of title_band_height (camera.h): the
  // first line in the body font (a side-by-side view's method), the others small (what it
  // is), each cut to the plot's width; a failed run's banner goes below it. Empty: none.
  std::vector<std::string> title;
  // Replaces the scene's fixed camera (a live view's pan and zoom); pixels of this frame.
  std::optional<Camera> camera;
  // Where the frame goes: the renderer's own framebuffer (read_pixels) by default, or this
  // GL framebuffer (0: a window's back buffer) of the renderer's size. A window drawn
  // into directly needs no full-frame copy (a textured pass over every pixel, which a
  // software rasterizer pays in full); read_pixels then keeps the frame drawn before.
  std::optional<unsigned> framebuffer;
};

struct GlResources;

class Renderer {
 public:
  // Loads GL through `get_proc_address` from the current context and builds the
  // shaders, the font atlas and a width x height framebuffer. Returns null and a
  // one-line *error on failure. `max_samples` > 1 adds multisampling on top of the
  // analytic antialiasing; the default (1) is what `invfree render` and the goldens use,
  // and what makes a live frame equal an offscreen one.
  static std::unique_ptr<Renderer> create(GlGetProcAddress get_proc_address, int width, int height,
                                          std::string* error, int max_samples = 1);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Changes the frame size (framebuffers and font sizes follow). Returns "" or an error.
  std::string resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const;  // multisampling used (1: none)
  // The layout of a frame with or without the panel.
  FrameLayout layout(bool panel = true) const {
    return frame_layout(width(), height(), panel ? PanelMode::Side : PanelMode::Hidden,
                        text_scale_);
  }
  FrameLayout layout(PanelMode panel) const {
    return frame_layout(width(), height(), panel, text_scale_);
  }
  // The fixed camera of `scene` (for picking: camera.to_world(pixel)).
  Camera camera(const SceneDef& scene, bool panel = true) const {
    return scene_camera(scene, layout(panel));
  }
  // Enlarges the panel and its text by `scale` (the live window's UI scale; default 1).
  void set_text_scale(double scale);
  double text_scale() const { return text_scale_; }

  void draw(const FrameState& state, const DrawOptions& options = {});

  // The last frame drawn into the renderer's own framebuffer, RGBA8, width * height * 4
  // bytes, bottom row first (GL order).
  void read_pixels(std::vector<std::uint8_t>* rgba_bottom_up) const;

 private:
  Renderer();
  std::unique_ptr<GlResources> gl_;
  int width_ = 0, height_ = 0;
  int max_samples_ = 1;
  double text_scale_ = 1.0;
  void build_fonts();
};

}  // namespace invfree::render
