#include "app/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/colormap.h"
#include "app/render/frame_text.h"
#include "app/render/gl_api.h"
#include "app/render/shader_sources.h"
#include "app/render/text_atlas.h"

namespace invfree::render {

namespace {

struct Rgba {
  float r, g, b, a;
};
constexpr Rgba rgba(Rgb c, float a = 1.0f) {
  return {c.r, c.g, c.b, a};
}

// The figure's palette (the det F colours come from app/colormap.h).
constexpr Rgba kPlotBackground{0.955f, 0.96f, 0.968f, 1.0f};  // so that white (det F = 1) shows
constexpr Rgba kPanelBackground{1.0f, 1.0f, 1.0f, 1.0f};
constexpr Rgba kInk{0.12f, 0.12f, 0.12f, 1.0f};
constexpr Rgba kMutedInk{0.38f, 0.38f, 0.38f, 1.0f};
constexpr Rgba kSeparator{0.84f, 0.84f, 0.84f, 1.0f};
constexpr Rgba kPlaneFill{0.90f, 0.90f, 0.90f, 1.0f};
constexpr Rgba kPlaneHatch{0.60f, 0.60f, 0.60f, 1.0f};
constexpr Rgba kPlaneEdge{0.22f, 0.22f, 0.22f, 1.0f};
constexpr Rgba kMeshEdge{0.08f, 0.08f, 0.08f, 0.38f};
constexpr Rgba kOutline{0.08f, 0.08f, 0.08f, 1.0f};
constexpr Rgba kInvertedInk{0.0f, 0.50f, 0.10f, 1.0f};  // the inverted green, dark enough for text

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

void add_triangle(Shapes& s, Vec2 a, Vec2 b, Vec2 c, Rgba ca, Rgba cb, Rgba cc) {
  s.push_back({float(a.x()), float(a.y()), ca});
  s.push_back({float(b.x()), float(b.y()), cb});
  s.push_back({float(c.x()), float(c.y()), cc});
}
void add_triangle(Shapes& s, Vec2 a, Vec2 b, Vec2 c, Rgba color) {
  add_triangle(s, a, b, c, color, color, color);
}

// Axis-aligned rectangle; colour `top` at y0 and `bottom` at y1 (a vertical gradient).
void add_rect(Shapes& s, double x0, double y0, double x1, double y1, Rgba top, Rgba bottom) {
  add_triangle(s, {x0, y0}, {x1, y0}, {x1, y1}, top, top, bottom);
  add_triangle(s, {x0, y0}, {x1, y1}, {x0, y1}, top, bottom, bottom);
}
void add_rect(Shapes& s, double x0, double y0, double x1, double y1, Rgba color) {
  add_rect(s, x0, y0, x1, y1, color, color);
}

// A straight stroke of the given width, antialiased across its length by the shader
// (the quad is one pixel wider on each side for the coverage ramp) and extended by half
// its width past both ends so that strokes meeting at an angle leave no notch.
void add_segment(Shapes& s, Vec2 a, Vec2 b, double width, Rgba color) {
  Vec2 d = b - a;
  const double len = d.norm();
  if (!(len > 0.0)) return;
  d /= len;
  const double half = 0.5 * width, outer = half + 1.0;
  const Vec2 n(-d.y() * outer, d.x() * outer);
  const Vec2 e = d * half;
  const Vec2 p[4] = {a - e + n, b + e + n, b + e - n, a - e - n};
  const float across[4] = {float(outer), float(outer), float(-outer), float(-outer)};
  for (int k : {0, 1, 2, 0, 2, 3})
    s.push_back({float(p[k].x()), float(p[k].y()), color, across[k], float(half)});
}

void add_rect_outline(Shapes& s, double x0, double y0, double x1, double y1, double width,
                      Rgba color) {
  const double h = 0.5 * width;
  add_rect(s, x0 - h, y0 - h, x1 + h, y0 + h, color);
  add_rect(s, x0 - h, y1 - h, x1 + h, y1 + h, color);
  add_rect(s, x0 - h, y0 + h, x0 + h, y1 - h, color);
  add_rect(s, x1 - h, y0 + h, x1 + h, y1 - h, color);
}

std::string compile_error(const GlApi& gl, GLuint object, bool program) {
  char log[2048] = {};
  if (program)
    gl.GetProgramInfoLog(object, sizeof log, nullptr, log);
  else
    gl.GetShaderInfoLog(object, sizeof log, nullptr, log);
  std::string s(log);
  for (char& c : s)
    if (c == '\n') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

GLuint build_program(const GlApi& gl, const char* name, const char* vertex, const char* fragment,
                     std::string* error) {
  GLuint shaders[2] = {gl.CreateShader(GL_VERTEX_SHADER), gl.CreateShader(GL_FRAGMENT_SHADER)};
  const std::string texts[2] = {glsl_for_context(vertex, gl.opengl_es),
                                glsl_for_context(fragment, gl.opengl_es)};
  const char* sources[2] = {texts[0].c_str(), texts[1].c_str()};
  for (int i = 0; i < 2; ++i) {
    gl.ShaderSource(shaders[i], 1, &sources[i], nullptr);
    gl.CompileShader(shaders[i]);
    GLint ok = 0;
    gl.GetShaderiv(shaders[i], GL_COMPILE_STATUS, &ok);
    if (!ok) {
      *error = std::string("shader ") + name + (i == 0 ? "_vertex" : "_fragment") +
               ".glsl does not compile: " + compile_error(gl, shaders[i], false);
      gl.DeleteShader(shaders[0]);
      gl.DeleteShader(shaders[1]);
      return 0;
    }
  }
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, shaders[0]);
  gl.AttachShader(program, shaders[1]);
  gl.LinkProgram(program);
  gl.DeleteShader(shaders[0]);
  gl.DeleteShader(shaders[1]);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    *error = std::string("shader program ") + name +
             " does not link: " + compile_error(gl, program, true);
    gl.DeleteProgram(program);
    return 0;
  }
  return program;
}

// Edges of a triangle list, each once, split into interior ones (two triangles) and the
// boundary (one triangle).
void mesh_edges(const std::vector<std::array<int, 3>>& triangles,
                std::vector<std::pair<int, int>>* interior,
                std::vector<std::pair<int, int>>* boundary) {
  std::vector<std::pair<int, int>> all;
  all.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      all.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(all.begin(), all.end());
  interior->clear();
  boundary->clear();
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j] == all[i]) ++j;
    (j - i == 1 ? boundary : interior)->push_back(all[i]);
    i = j;
  }
}

}  // namespace

struct GlResources {
  GlApi gl;
  GLuint shape_program = 0, fill_program = 0, text_program = 0;
  GLint fill_frame_size = -1;
  GLint shape_frame_size = -1, shape_hatch = -1, shape_hatch_color = -1;
  GLint text_frame_size = -1, text_atlas_size = -1, text_atlas = -1;
  GLuint shape_vao = 0, shape_vbo = 0, text_vao = 0, text_vbo = 0;
  GLuint atlas_texture = 0;
  GLuint draw_fbo = 0, draw_rb = 0;  // multisampled target (0 when drawing single-sampled)
  GLuint resolve_fbo = 0, resolve_texture = 0;
  int samples = 1;
  TextAtlas atlas;
  std::vector<double> font_sizes;
  // Per-frame scratch, kept to avoid reallocating.
  Shapes shapes, hatched;
  std::vector<TextVertex> text;
  std::vector<GlyphQuad> glyphs;
  // The mesh's edges, and the triangles they were found from: the sort is redone only
  // when the mesh changes (every frame of a 64x64 mesh it would cost ~0.4 ms).
  std::vector<std::pair<int, int>> interior_edges, boundary_edges;
  std::vector<std::array<int, 3>> edges_of;

  void release_framebuffers() {
    if (draw_fbo) gl.DeleteFramebuffers(1, &draw_fbo);
    if (draw_rb) gl.DeleteRenderbuffers(1, &draw_rb);
    if (resolve_fbo) gl.DeleteFramebuffers(1, &resolve_fbo);
    if (resolve_texture) gl.DeleteTextures(1, &resolve_texture);
    draw_fbo = draw_rb = resolve_fbo = resolve_texture = 0;
  }

  void add_text(std::string_view s, int size, double x, double baseline, Rgba color,
                double align = 0.0) {
    if (align != 0.0) x -= align * atlas.text_width(s, size);
    glyphs.clear();
    atlas.layout(s, size, x, baseline, &glyphs);
    for (const GlyphQuad& q : glyphs) {
      const TextVertex v00{q.x0, q.y0, q.u0, q.v0, color}, v10{q.x1, q.y0, q.u1, q.v0, color};
      const TextVertex v11{q.x1, q.y1, q.u1, q.v1, color}, v01{q.x0, q.y1, q.u0, q.v1, color};
      text.insert(text.end(), {v00, v10, v11, v00, v11, v01});
    }
  }
};

// The side panel: scene, model, Lame parameters, time, step, det F extremes, and the
// colour bar with its ticks, the min/max markers and the det F <= 0 swatch.
// Returns the end of its opaque backdrop in res.shapes (what can be drawn without blending).
static size_t draw_panel(GlResources& res, const FrameLayout& L, const FrameState& state,
                         double det_lo, double det_hi, int inverted) {
  const SceneDef& scene = state.scene;
  const double s = L.scale;
  Shapes& panel = res.shapes;
  add_rect(panel, L.panel.x, 0, L.panel.x + L.panel.w, L.height, kPanelBackground);
  add_rect(panel, L.panel.x, 0, L.panel.x + std::max(1.0, std::round(s)), L.height, kSeparator);
  const size_t backdrop_end = panel.size();
  const double pad = std::round(26.0 * s);
  const double x0 = L.panel.x + pad;
  const double body = res.font_sizes[kBody], small = res.font_sizes[kSmall];
  double y = pad + res.atlas.ascent(kTitle);
  res.add_text(scene.name, kTitle, x0, y, kInk);
  y += 1.25 * body;
  res.add_text(model_display_name(scene.model), kBody, x0, y, kMutedInk);
  y += 1.3 * body;
  res.add_text("μ = " + format_si(scene.lame.mu, "Pa"), kBody, x0, y, kMutedInk);
  y += 1.3 * body;
  res.add_text("λ = " + format_si(scene.lame.lambda, "Pa"), kBody, x0, y, kMutedInk);
  y += 2.0 * body;
  res.add_text(format_time(state.time, scene.h), kBody, x0, y, kInk);
  y += 1.3 * body;
  res.add_text("step " + std::to_string(state.step), kBody, x0, y, kInk);
  y += 2.0 * body;
  char buf[64];
  std::snprintf(buf, sizeof buf, "min det F = %.3f", det_lo);
  res.add_text(buf, kBody, x0, y, kInk);
  y += 1.3 * body;
  std::snprintf(buf, sizeof buf, "max det F = %.3f", det_hi);
  res.add_text(buf, kBody, x0, y, kInk);
  if (inverted > 0) {
    y += 1.3 * body;
    res.add_text(
        "inverted: " + std::to_string(inverted) + (inverted == 1 ? " triangle" : " triangles"),
        kBody, x0, y, kInvertedInk);
  }

  // Colour bar: vertical, stretch up, with the det F <= 0 swatch below it.
  const double bar_w = std::round(24.0 * s), marker = std::round(9.0 * s);
  const double bar_x0 = x0 + marker + std::round(4.0 * s), bar_x1 = bar_x0 + bar_w;
  const double swatch_h = std::round(20.0 * s);
  const double swatch_y1 = L.height - pad, swatch_y0 = swatch_y1 - swatch_h;
  const double bar_y1 = std::round(swatch_y0 - 1.6 * small);
  const double bar_title_y = y + 2.0 * body;
  const double bar_y0 = std::round(bar_title_y + 0.9 * small);
  res.add_text("det F", kBody, x0, bar_title_y, kInk);
  const auto bar_y = [&](double t) { return bar_y1 - 0.5 * (t + 1.0) * (bar_y1 - bar_y0); };
  for (int k = 0; k < 6; ++k) {  // the colormap's seven stops: piecewise linear, exact
    const double t0 = -1.0 + k / 3.0, t1 = -1.0 + (k + 1) / 3.0;
    add_rect(panel, bar_x0, bar_y(t1), bar_x1, bar_y(t0), rgba(diverging_color(t1)),
             rgba(diverging_color(t0)));
  }
  const double thin = std::max(1.0, std::round(s));
  add_rect_outline(panel, bar_x0, bar_y0, bar_x1, bar_y1, thin, kMutedInk);
  const double tick_len = std::round(6.0 * s), label_x = bar_x1 + tick_len + std::round(6.0 * s);
  double label_right = label_x;
  for (const ColorBarTick& t : color_bar_ticks(kDetFRange)) {
    const double ty = std::round(bar_y(t.position));
    add_rect(panel, bar_x1, ty - 0.5 * thin, bar_x1 + tick_len, ty + 0.5 * thin, kMutedInk);
    res.add_text(t.label, kSmall, label_x, ty + 0.36 * small, kInk);
    label_right = std::max(label_right, label_x + res.atlas.text_width(t.label, kSmall));
  }
  const double note_x = label_right + std::round(14.0 * s);
  res.add_text("stretch", kSmall, note_x, bar_y(1.0) + 0.36 * small, kMutedInk);
  res.add_text("compression", kSmall, note_x, bar_y(-1.0) + 0.36 * small, kMutedInk);
  add_rect(panel, bar_x0, swatch_y0, bar_x1, swatch_y1, rgba(kInvertedColor));
  add_rect_outline(panel, bar_x0, swatch_y0, bar_x1, swatch_y1, thin, kMutedInk);
  res.add_text("det F ≤ 0 (inverted)", kSmall, label_x,
               0.5 * (swatch_y0 + swatch_y1) + 0.36 * small, kInk);
  // Markers (a glyph, so antialiased like the text) at the current min and max det F,
  // beside the swatch when inverted.
  for (const double d : {det_lo, det_hi}) {
    const double my = d > 0.0 ? bar_y(det_f_scale_position(d)) : 0.5 * (swatch_y0 + swatch_y1);
    const double mx = bar_x0 - std::round(2.0 * s) - res.atlas.text_width("▶", kSmall);
    res.add_text("▶", kSmall, mx, my - res.atlas.ink_middle(kSmall, U'▶'), kInk);
  }
  return backdrop_end;
}

Renderer::Renderer() : gl_(std::make_unique<GlResources>()) {}

Renderer::~Renderer() {
  if (!gl_) return;
  const GlApi& gl = gl_->gl;
  if (gl.DeleteProgram == nullptr) return;
  gl_->release_framebuffers();
  gl.DeleteProgram(gl_->shape_program);
  gl.DeleteProgram(gl_->fill_program);
  gl.DeleteProgram(gl_->text_program);
  const GLuint buffers[] = {gl_->shape_vbo, gl_->text_vbo};
  gl.DeleteBuffers(2, buffers);
  const GLuint arrays[] = {gl_->shape_vao, gl_->text_vao};
  gl.DeleteVertexArrays(2, arrays);
  gl.DeleteTextures(1, &gl_->atlas_texture);
}

std::unique_ptr<Renderer> Renderer::create(GlGetProcAddress get_proc_address, int width, int height,
                                           std::string* error, int max_samples) {
  std::unique_ptr<Renderer> r(new Renderer());
  r->max_samples_ = std::max(1, max_samples);
  GlResources& res = *r->gl_;
  if (auto e = load_gl_api(get_proc_address, &res.gl); !e.empty()) {
    *error = e;
    r->gl_->gl = GlApi{};
    return nullptr;
  }
  const GlApi& gl = res.gl;
  const ShaderSources& src = shader_sources();
  res.shape_program = build_program(gl, "shape", src.shape_vertex, src.shape_fragment, error);
  if (!res.shape_program) return nullptr;
  res.fill_program = build_program(gl, "fill", src.shape_vertex, src.fill_fragment, error);
  if (!res.fill_program) return nullptr;
  res.text_program = build_program(gl, "text", src.text_vertex, src.text_fragment, error);
  if (!res.text_program) return nullptr;
  res.shape_frame_size = gl.GetUniformLocation(res.shape_program, "frame_size");
  res.fill_frame_size = gl.GetUniformLocation(res.fill_program, "frame_size");
  res.shape_hatch = gl.GetUniformLocation(res.shape_program, "hatch");
  res.shape_hatch_color = gl.GetUniformLocation(res.shape_program, "hatch_color");
  res.text_frame_size = gl.GetUniformLocation(res.text_program, "frame_size");
  res.text_atlas_size = gl.GetUniformLocation(res.text_program, "atlas_size");
  res.text_atlas = gl.GetUniformLocation(res.text_program, "atlas");

  GLint previous_vao = 0;
  gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &previous_vao);
  gl.GenVertexArrays(1, &res.shape_vao);
  gl.GenBuffers(1, &res.shape_vbo);
  gl.BindVertexArray(res.shape_vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, res.shape_vbo);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(ShapeVertex),
                         reinterpret_cast<void*>(offsetof(ShapeVertex, x)));
  gl.EnableVertexAttribArray(1);
  gl.VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(ShapeVertex),
                         reinterpret_cast<void*>(offsetof(ShapeVertex, c)));
  gl.EnableVertexAttribArray(2);
  gl.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(ShapeVertex),
                         reinterpret_cast<void*>(offsetof(ShapeVertex, across)));
  gl.GenVertexArrays(1, &res.text_vao);
  gl.GenBuffers(1, &res.text_vbo);
  gl.BindVertexArray(res.text_vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, res.text_vbo);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(TextVertex),
                         reinterpret_cast<void*>(offsetof(TextVertex, x)));
  gl.EnableVertexAttribArray(1);
  gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(TextVertex),
                         reinterpret_cast<void*>(offsetof(TextVertex, u)));
  gl.EnableVertexAttribArray(2);
  gl.VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(TextVertex),
                         reinterpret_cast<void*>(offsetof(TextVertex, c)));
  gl.BindVertexArray(static_cast<GLuint>(previous_vao));
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  gl.GenTextures(1, &res.atlas_texture);

  if (auto e = r->resize(width, height); !e.empty()) {
    *error = e;
    return nullptr;
  }
  return r;
}

int Renderer::samples() const {
  return gl_->samples;
}

std::string Renderer::resize(int width, int height) {
  GlResources& res = *gl_;
  const GlApi& gl = res.gl;
  GLint max_size = 0, max_samples = 0;
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    return "frame size " + std::to_string(width) + "x" + std::to_string(height) +
           " is outside 1.." + std::to_string(max_size) + " pixels";
  res.release_framebuffers();
  width_ = width;
  height_ = height;

  GLint previous_draw = 0, previous_read = 0, previous_texture = 0;
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_draw);
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);
  gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &previous_texture);

  gl.GenTextures(1, &res.resolve_texture);
  gl.BindTexture(GL_TEXTURE_2D, res.resolve_texture);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  // Read back (read_pixels), never sampled; a filter without mipmaps keeps it complete.
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.GenFramebuffers(1, &res.resolve_fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, res.resolve_fbo);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, res.resolve_texture,
                          0);
  std::string error;
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    error = "cannot create the frame's framebuffer";

  res.samples = std::min(max_samples_, static_cast<int>(max_samples));
  if (error.empty() && res.samples > 1) {
    gl.GenRenderbuffers(1, &res.draw_rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, res.draw_rb);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, res.samples, GL_RGBA8, width, height);
    gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl.GenFramebuffers(1, &res.draw_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, res.draw_fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, res.draw_rb);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      // No multisampling then: draw straight into the resolve target.
      gl.DeleteFramebuffers(1, &res.draw_fbo);
      gl.DeleteRenderbuffers(1, &res.draw_rb);
      res.draw_fbo = res.draw_rb = 0;
      res.samples = 1;
    }
  }
  if (res.samples <= 1) res.samples = 1;

  // Fonts scale with the frame (designed at 1280x720), never below a legible size.
  const double s = frame_layout(width, height).scale;
  res.font_sizes = {std::max(13.0, std::round(31.0 * s)), std::max(11.0, std::round(21.0 * s)),
                    std::max(10.0, std::round(18.0 * s))};
  res.atlas.build(res.font_sizes);
  gl.BindTexture(GL_TEXTURE_2D, res.atlas_texture);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, res.atlas.width(), res.atlas.height(), 0, GL_RED,
                GL_UNSIGNED_BYTE, res.atlas.pixels().data());
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous_texture));
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_draw));
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
  return error;
}

FrameState capture_frame_state(const Simulation& sim, const std::vector<double>* det_f) {
  FrameState f;
  f.scene = sim.scene;
  f.x = sim.x;
  f.triangles = sim.mesh.triangles;
  f.det_f = det_f ? *det_f : triangle_det_f(sim);
  f.ceiling_y = sim.ceiling_y;
  f.time = sim.time;
  f.step = sim.step_count;
  return f;
}

void Renderer::draw(const FrameState& state, const DrawOptions& options) {
  GlResources& res = *gl_;
  const GlApi& gl = res.gl;
  const FrameLayout L = frame_layout(width_, height_, options.panel);
  const double s = L.scale;
  const SceneDef& scene = state.scene;
  const Camera cam = options.camera ? *options.camera : scene_camera(scene, L);
  res.shapes.clear();
  res.hatched.clear();
  res.text.clear();

  // --- The world, clipped to the plot area.
  const double px0 = L.plot.x, px1 = L.plot.x + L.plot.w, py0 = L.plot.y, py1 = L.plot.y + L.plot.h;
  const double plane_line = std::max(1.5, 2.5 * s);
  Shapes& world = res.shapes;
  // Each plane: a filled half-plane whose surface layer is hatched (the drawing
  // convention for a rigid support), so that a large ceiling does not fill the picture
  // with stripes.
  const double band = std::round(std::max(10.0, 30.0 * s));
  if (scene.has_ground) {
    const double gy = cam.to_pixel(Vec2(0.0, scene.ground_y)).y();
    const double y_end = std::max(gy, py1), y_band = std::min(gy + band, y_end);
    add_rect(res.hatched, px0, gy, px1, y_band, kPlaneFill);
    add_rect(world, px0, y_band, px1, y_end, kPlaneFill);
  }
  if (scene.has_ceiling) {
    const double cy = cam.to_pixel(Vec2(0.0, state.ceiling_y)).y();
    const double y_end = std::min(py0, cy), y_band = std::max(cy - band, y_end);
    add_rect(res.hatched, px0, y_band, px1, cy, kPlaneFill);
    add_rect(world, px0, y_end, px1, y_band, kPlaneFill);
  }
  const int nodes = static_cast<int>(state.x.size() / 2);
  std::vector<Vec2> p(static_cast<size_t>(nodes));
  for (int i = 0; i < nodes; ++i) p[i] = cam.to_pixel(Vec2(state.x[2 * i], state.x[2 * i + 1]));
  double det_lo = 1.0, det_hi = 1.0;
  int inverted = 0;
  // Inverted triangles last: they overlap their neighbours (they are folded over), and
  // drawn first they would be hidden under them.
  for (const bool inverted_pass : {false, true}) {
    for (size_t t = 0; t < state.triangles.size(); ++t) {
      const double d = t < state.det_f.size() ? state.det_f[t] : 1.0;
      if (!(d > 0.0) != inverted_pass) continue;
      const auto& tri = state.triangles[t];
      add_triangle(world, p[tri[0]], p[tri[1]], p[tri[2]], rgba(det_f_color(d)));
    }
  }
  for (size_t t = 0; t < state.triangles.size(); ++t) {
    const double d = t < state.det_f.size() ? state.det_f[t] : 1.0;
    if (t == 0) det_lo = det_hi = d;
    det_lo = std::min(det_lo, d);
    det_hi = std::max(det_hi, d);
    if (!(d > 0.0)) ++inverted;
  }
  const size_t world_fills = world.size();  // opaque so far; the strokes below blend
  if (state.triangles != res.edges_of) {
    mesh_edges(state.triangles, &res.interior_edges, &res.boundary_edges);
    res.edges_of = state.triangles;
  }
  if (options.edges) {
    const double w = std::max(1.0, 1.1 * s);
    for (const auto& [a, b] : res.interior_edges) add_segment(world, p[a], p[b], w, kMeshEdge);
  }
  const double outline = std::max(1.25, 1.8 * s);
  for (const auto& [a, b] : res.boundary_edges) add_segment(world, p[a], p[b], outline, kOutline);
  if (scene.has_ground) {
    const double gy = cam.to_pixel(Vec2(0.0, scene.ground_y)).y();
    add_segment(world, {px0 - 10, gy + 0.5 * plane_line}, {px1 + 10, gy + 0.5 * plane_line},
                plane_line, kPlaneEdge);
  }
  if (scene.has_ceiling) {
    const double cy = cam.to_pixel(Vec2(0.0, state.ceiling_y)).y();
    add_segment(world, {px0 - 10, cy - 0.5 * plane_line}, {px1 + 10, cy - 0.5 * plane_line},
                plane_line, kPlaneEdge);
  }
  const size_t world_vertices = world.size();

  // --- The panel: words, numbers and the colour bar (same vertex list, not clipped).
  const size_t panel_backdrop =
      options.panel ? draw_panel(res, L, state, det_lo, det_hi, inverted) : world_vertices;

  // --- GL: draw everything into the (multisampled) framebuffer, then resolve.
  GLint previous_draw = 0, previous_read = 0, viewport[4] = {};
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_draw);
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);
  gl.GetIntegerv(GL_VIEWPORT, viewport);
  const bool blend_was = gl.IsEnabled(GL_BLEND), scissor_was = gl.IsEnabled(GL_SCISSOR_TEST);

  const GLuint output = options.framebuffer ? *options.framebuffer : res.resolve_fbo;
  const GLuint target = res.draw_fbo ? res.draw_fbo : output;
  gl.BindFramebuffer(GL_FRAMEBUFFER, target);
  gl.Viewport(0, 0, L.width, L.height);
  gl.Disable(GL_SCISSOR_TEST);
  gl.ClearColor(kPlotBackground.r, kPlotBackground.g, kPlotBackground.b, kPlotBackground.a);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  // Opaque fills first and without blending (alpha 1: blending would change no pixel, but a
  // software rasterizer would read each one back). The antialiased strokes and the text
  // blend over them.
  gl.Disable(GL_BLEND);
  gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

  gl.BindVertexArray(res.shape_vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, res.shape_vbo);
  const auto draw_range = [&](size_t begin, size_t end) {
    gl.DrawArrays(GL_TRIANGLES, static_cast<GLint>(begin), static_cast<GLsizei>(end - begin));
  };
  // Clip the world to the plot area (GL's scissor box has its origin bottom-left).
  const auto clip_to_plot = [&](bool on) {
    if (!on) return gl.Disable(GL_SCISSOR_TEST);
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(
        static_cast<GLint>(std::lround(L.plot.x)), static_cast<GLint>(std::lround(L.height - py1)),
        static_cast<GLsizei>(std::lround(L.plot.w)), static_cast<GLsizei>(std::lround(L.plot.h)));
  };
  clip_to_plot(true);
  // The hatched bands of the planes (opaque).
  gl.UseProgram(res.shape_program);
  gl.Uniform2f(res.shape_frame_size, float(L.width), float(L.height));
  const float spacing = static_cast<float>(std::max(6.0, std::round(14.0 * s)));
  gl.Uniform4f(res.shape_hatch, spacing, static_cast<float>(std::max(1.0, 1.3 * s)), 1.0f, 0.0f);
  gl.Uniform4f(res.shape_hatch_color, kPlaneHatch.r, kPlaneHatch.g, kPlaneHatch.b, 1.0f);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(res.hatched.size() * sizeof(ShapeVertex)),
                res.hatched.data(), GL_STREAM_DRAW);
  draw_range(0, res.hatched.size());
  // The opaque fills: the world's, then the panel's backdrop.
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(res.shapes.size() * sizeof(ShapeVertex)),
                res.shapes.data(), GL_STREAM_DRAW);
  gl.UseProgram(res.fill_program);
  gl.Uniform2f(res.fill_frame_size, float(L.width), float(L.height));
  draw_range(0, world_fills);
  clip_to_plot(false);
  draw_range(world_vertices, panel_backdrop);
  // The antialiased strokes over the world's fills, and the panel's content.
  gl.UseProgram(res.shape_program);
  gl.Uniform4f(res.shape_hatch, 1.0f, 0.0f, 0.0f, 0.0f);
  gl.Enable(GL_BLEND);
  clip_to_plot(true);
  draw_range(world_fills, world_vertices);
  clip_to_plot(false);
  draw_range(panel_backdrop, res.shapes.size());

  gl.UseProgram(res.text_program);
  gl.Uniform2f(res.text_frame_size, float(L.width), float(L.height));
  gl.Uniform2f(res.text_atlas_size, float(res.atlas.width()), float(res.atlas.height()));
  gl.Uniform1i(res.text_atlas, 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, res.atlas_texture);
  gl.BindVertexArray(res.text_vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, res.text_vbo);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(res.text.size() * sizeof(TextVertex)),
                res.text.data(), GL_STREAM_DRAW);
  gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(res.text.size()));

  if (res.draw_fbo) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, res.draw_fbo);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, output);
    gl.BlitFramebuffer(0, 0, L.width, L.height, 0, 0, L.width, L.height, GL_COLOR_BUFFER_BIT,
                       GL_NEAREST);
  }

  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  gl.BindVertexArray(0);
  gl.UseProgram(0);
  if (!blend_was) gl.Disable(GL_BLEND);
  if (scissor_was) gl.Enable(GL_SCISSOR_TEST);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_draw));
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
  gl.Viewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void Renderer::read_pixels(std::vector<std::uint8_t>* rgba) const {
  const GlApi& gl = gl_->gl;
  GLint previous_read = 0;
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);
  rgba->resize(static_cast<size_t>(width_) * height_ * 4);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, gl_->resolve_fbo);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba->data());
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
}

}  // namespace invfree::render
