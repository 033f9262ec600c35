#include "app/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>

#include "app/render/frame_vertices.h"
#include "app/render/gl_api.h"
#include "app/render/shader_sources.h"
#include "app/render/text_atlas.h"
#include "potential/mass_spring.h"
#include "scene/reduced_basis.h"
#include "solver/step_workspace.h"

namespace invfree::render {

namespace {

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

// Replaces the bound GL_ARRAY_BUFFER's contents with `vertices`.
template <class Vertex>
void upload(const GlApi& gl, const std::vector<Vertex>& vertices) {
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)),
                vertices.data(), GL_STREAM_DRAW);
}

// One float vertex attribute: its location, component count and offset in the vertex.
struct VertexAttribute {
  GLuint index;
  GLint size;
  size_t offset;
};

// A vertex array over a new buffer of vertices `stride` bytes apart; leaves both bound.
void make_vertex_array(const GlApi& gl, GLuint* vao, GLuint* vbo, size_t stride,
                       std::initializer_list<VertexAttribute> attributes) {
  gl.GenVertexArrays(1, vao);
  gl.GenBuffers(1, vbo);
  gl.BindVertexArray(*vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, *vbo);
  for (const VertexAttribute& a : attributes) {
    gl.EnableVertexAttribArray(a.index);
    gl.VertexAttribPointer(a.index, a.size, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                           reinterpret_cast<void*>(a.offset));
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
  FrameVertices vertices;  // the last frame's, kept to avoid reallocating

  void release_framebuffers() {
    if (draw_fbo) gl.DeleteFramebuffers(1, &draw_fbo);
    if (draw_rb) gl.DeleteRenderbuffers(1, &draw_rb);
    if (resolve_fbo) gl.DeleteFramebuffers(1, &resolve_fbo);
    if (resolve_texture) gl.DeleteTextures(1, &resolve_texture);
    draw_fbo = draw_rb = resolve_fbo = resolve_texture = 0;
  }
};

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
  make_vertex_array(gl, &res.shape_vao, &res.shape_vbo, sizeof(ShapeVertex),
                    {{0, 2, offsetof(ShapeVertex, x)},
                     {1, 4, offsetof(ShapeVertex, c)},
                     {2, 2, offsetof(ShapeVertex, across)}});
  make_vertex_array(gl, &res.text_vao, &res.text_vbo, sizeof(TextVertex),
                    {{0, 2, offsetof(TextVertex, x)},
                     {1, 2, offsetof(TextVertex, u)},
                     {2, 4, offsetof(TextVertex, c)}});
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

  build_fonts();

  gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous_texture));
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_draw));
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
  return error;
}

// The font atlas at the sizes of this frame size and text scale; leaves the atlas texture
// bound (the callers restore their binding).
void Renderer::build_fonts() {
  GlResources& res = *gl_;
  const GlApi& gl = res.gl;
  // Fonts scale with the frame (designed at 1280x720), never below a legible size.
  const double s = layout().scale;
  res.vertices.font_sizes = {std::max(13.0, std::round(31.0 * s)),
                             std::max(11.0, std::round(21.0 * s)),
                             std::max(10.0, std::round(18.0 * s))};
  res.atlas.build(res.vertices.font_sizes);
  res.vertices.atlas = &res.atlas;
  gl.BindTexture(GL_TEXTURE_2D, res.atlas_texture);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, res.atlas.width(), res.atlas.height(), 0, GL_RED,
                GL_UNSIGNED_BYTE, res.atlas.pixels().data());
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void Renderer::set_text_scale(double scale) {
  if (!(scale > 0.0) || scale == text_scale_) return;
  text_scale_ = scale;
  GLint previous_texture = 0;
  gl_->gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &previous_texture);
  build_fonts();
  gl_->gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous_texture));
}

namespace {

// Each triangle's principal Cauchy stresses (larger first) and the first one's unit
// direction, for the stress glyphs.
void principal_stresses(const Simulation& sim, std::vector<Vec2>* values,
                        std::vector<Vec2>* directions) {
  const size_t n = static_cast<size_t>(sim.mesh.triangle_count());
  values->resize(n);
  directions->resize(n);
  for (size_t t = 0; t < n; ++t) {
    const int i = static_cast<int>(t);
    const PrincipalStress p = principal_stress_of(
        sim.scene.model, triangle_deformation_gradient(sim, i), triangle_material(sim, i));
    (*values)[t] = p.values;
    (*directions)[t] = p.direction;
  }
}

// The mesh's spacing: the side of a right isosceles triangle of the mean rest area (a
// square mesh's cell side); 0 without triangles.
double mesh_spacing(const Mesh& mesh) {
  if (mesh.rest_area.empty()) return 0.0;
  double area = 0.0;
  for (const double a : mesh.rest_area) area += std::abs(a);
  return std::sqrt(2.0 * area / static_cast<double>(mesh.rest_area.size()));
}

}  // namespace

double particle_dot_radius(const std::vector<Vec2>& rest,
                           const std::vector<std::array<int, 2>>& springs) {
  constexpr double kLoneParticle = 0.1;  // the tutorial's simulator0/1 (m)
  std::vector<double> lengths;
  lengths.reserve(springs.size());
  const int n = static_cast<int>(rest.size());
  for (const auto& [a, b] : springs) {
    if (a < 0 || b < 0 || a >= n || b >= n) continue;
    const double l = (rest[static_cast<size_t>(a)] - rest[static_cast<size_t>(b)]).norm();
    if (l > 0.0 && std::isfinite(l)) lengths.push_back(l);
  }
  if (lengths.empty()) return kLoneParticle;
  const auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return std::min(kLoneParticle, 0.1 * *mid);
}

Overlay particle_overlay(const VecX& x, const std::vector<std::array<int, 2>>& springs,
                         double dot_radius) {
  Overlay o;
  const int n = static_cast<int>(x.size() / 2);
  o.points.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) o.points[static_cast<size_t>(i)] = Vec2(x[2 * i], x[2 * i + 1]);
  for (const auto& [a, b] : springs)
    if (a >= 0 && b >= 0 && a < n && b < n && a != b) o.segments.push_back({a, b});
  o.color = kParticleColor;
  o.dot_radius = dot_radius;
  o.stroke_width = 1.5;
  return o;
}

Overlay anchor_overlay(const std::array<Vec2, 3>& corners, double spacing) {
  Overlay o;
  o.points.assign(corners.begin(), corners.end());
  o.segments = {{0, 1}, {1, 2}, {2, 0}};
  o.color = kAnchorColor;
  o.dot_radius = 0.2 * spacing;  // twice the tutorial's 0.1 side / n_seg, to be seen
  o.stroke_width = 2.5;
  return o;
}

FrameState capture_frame_state(const Simulation& sim, const std::vector<double>* det_f,
                               const CaptureOptions& capture) {
  FrameState f;
  f.scene = sim.scene;
  f.x = sim.x;
  f.triangles = sim.mesh.triangles;
  f.det_f = det_f ? *det_f : triangle_det_f(sim);
  f.color_by = capture.color_by;
  if (capture.color_by == TriangleField::DetF)
    f.field = f.det_f;
  else
    triangle_field(sim, capture.color_by, &f.field);
  if (capture.stress_glyphs && sim.scene.has_triangle_elasticity())
    principal_stresses(sim, &f.principal_stress, &f.principal_direction);
  if (sim.mesh.triangles.empty() && sim.mesh.node_count() > 0) {
    // Particles (the course's chapter 0): no triangles to fill, so the nodes and springs.
    const std::vector<std::array<int, 2>> springs = sim.workspace
                                                        ? spring_node_pairs(sim.workspace->springs)
                                                        : std::vector<std::array<int, 2>>{};
    f.overlays.push_back(
        particle_overlay(sim.x, springs, particle_dot_radius(sim.mesh.rest, springs)));
  }
  if (const auto anchors = affine_anchor_triangle(sim.scene, sim.mesh, sim.x))
    f.overlays.push_back(anchor_overlay(*anchors, mesh_spacing(sim.mesh)));
  f.body_begin = sim.mesh.body_begin;
  f.ceiling_y = sim.ceiling_y;
  f.time = sim.time;
  f.step = sim.step_count;
  return f;
}

// The GL state draw changes and restores: framebuffer bindings, viewport, blending, scissor.
struct SavedGlState {
  GLint draw = 0, read = 0, viewport[4] = {};
  bool blend = false, scissor = false;

  explicit SavedGlState(const GlApi& gl) {
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    gl.GetIntegerv(GL_VIEWPORT, viewport);
    blend = gl.IsEnabled(GL_BLEND);
    scissor = gl.IsEnabled(GL_SCISSOR_TEST);
  }
  void restore(const GlApi& gl) const {
    if (!blend) gl.Disable(GL_BLEND);
    if (scissor) gl.Enable(GL_SCISSOR_TEST);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
    gl.Viewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  }
};

// The text (res.vertices.text), blended, with the font atlas.
static void draw_text_vertices(GlResources& res, const FrameLayout& L) {
  const GlApi& gl = res.gl;
  gl.UseProgram(res.text_program);
  gl.Uniform2f(res.text_frame_size, float(L.width), float(L.height));
  gl.Uniform2f(res.text_atlas_size, float(res.atlas.width()), float(res.atlas.height()));
  gl.Uniform1i(res.text_atlas, 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, res.atlas_texture);
  gl.BindVertexArray(res.text_vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, res.text_vbo);
  upload(gl, res.vertices.text);
  gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(res.vertices.text.size()));
}

// Draws the vertex lists into `output` (through the multisampled framebuffer when there is
// one): opaque fills first and without blending (alpha 1: blending would change no pixel,
// but a software rasterizer would read each one back), then the antialiased strokes and
// the text blended over them; the world clipped to the plot area.
static void draw_vertices(GlResources& res, const FrameLayout& L, const ShapeRanges& r,
                          GLuint output) {
  const GlApi& gl = res.gl;
  const double s = L.scale;
  const GLuint target = res.draw_fbo ? res.draw_fbo : output;
  gl.BindFramebuffer(GL_FRAMEBUFFER, target);
  gl.Viewport(0, 0, L.width, L.height);
  gl.Disable(GL_SCISSOR_TEST);
  gl.ClearColor(kPlotBackground.r, kPlotBackground.g, kPlotBackground.b, kPlotBackground.a);
  gl.Clear(GL_COLOR_BUFFER_BIT);
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
    gl.Scissor(static_cast<GLint>(std::lround(L.plot.x)),
               static_cast<GLint>(std::lround(L.height - (L.plot.y + L.plot.h))),
               static_cast<GLsizei>(std::lround(L.plot.w)),
               static_cast<GLsizei>(std::lround(L.plot.h)));
  };
  clip_to_plot(true);
  // The hatched bands of the planes (opaque).
  gl.UseProgram(res.shape_program);
  gl.Uniform2f(res.shape_frame_size, float(L.width), float(L.height));
  const float spacing = static_cast<float>(std::max(6.0, std::round(14.0 * s)));
  gl.Uniform4f(res.shape_hatch, spacing, static_cast<float>(std::max(1.0, 1.3 * s)), 1.0f, 0.0f);
  gl.Uniform4f(res.shape_hatch_color, kPlaneHatch.r, kPlaneHatch.g, kPlaneHatch.b, 1.0f);
  upload(gl, res.vertices.hatched);
  draw_range(0, res.vertices.hatched.size());
  // The opaque fills: the world's, then the panel's backdrop.
  upload(gl, res.vertices.shapes);
  gl.UseProgram(res.fill_program);
  gl.Uniform2f(res.fill_frame_size, float(L.width), float(L.height));
  draw_range(0, r.world_fills);
  const auto draw_world_strokes = [&] {  // antialiased, over the world's fills
    gl.UseProgram(res.shape_program);
    gl.Uniform4f(res.shape_hatch, 1.0f, 0.0f, 0.0f, 0.0f);
    gl.Enable(GL_BLEND);
    clip_to_plot(true);
    draw_range(r.world_fills, r.world_end);
    clip_to_plot(false);
  };
  if (!L.overlay) {  // the opaque backdrop beside the world, then the world's strokes
    clip_to_plot(false);
    draw_range(r.world_end, r.panel_backdrop);
    draw_world_strokes();
  } else {  // the world whole, then the translucent backdrop over it
    draw_world_strokes();
    gl.UseProgram(res.fill_program);
    draw_range(r.world_end, r.panel_backdrop);
    gl.UseProgram(res.shape_program);
  }
  // The panel's content.
  draw_range(r.panel_backdrop, res.vertices.shapes.size());
  draw_text_vertices(res, L);
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
}

void Renderer::draw(const FrameState& state, const DrawOptions& options) {
  GlResources& res = *gl_;
  const FrameLayout L =
      layout(!options.panel ? PanelMode::Hidden
                            : (options.panel_overlay ? PanelMode::Overlay : PanelMode::Side));
  const Camera cam = options.camera ? *options.camera : scene_camera(state.scene, L);
  const ShapeRanges ranges = build_frame_vertices(res.vertices, state, L, cam, options);
  const SavedGlState saved(res.gl);
  draw_vertices(res, L, ranges, options.framebuffer ? *options.framebuffer : res.resolve_fbo);
  saved.restore(res.gl);
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
