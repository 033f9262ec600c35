// Screenshot regression tests: deterministic frames of the built-in scenes rendered
// offscreen (OSMesa, no display) at a fixed size and fixed steps, compared with the PNG
// goldens in tests/render/goldens/ under the tolerance of image_compare.h. Each case also
// checks that the state it pictures is what its name claims (first contact, maximum
// compression, at rest, inverted triangles), so a golden cannot silently drift into
// showing something else. Regenerate: tests/render/regenerate_goldens.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/render/frame_vertices.h"
#include "app/render/gl_api.h"
#include "app/render/offscreen_context.h"
#include "app/render/renderer.h"
#include "collision/intersection_check.h"
#include "scene/boundary.h"
#include "scene/reduced_basis.h"
#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "solver/step_workspace.h"
#include "tests/render/image_compare.h"
#include "tests/test_paths.h"
#include "triangle_fields.h"

namespace invfree {
namespace {

constexpr int kWidth = 960, kHeight = 540;

// One offscreen context and renderer for the whole test program.
std::unique_ptr<render::OffscreenContext> g_context;
render::Renderer& renderer() {
  static std::unique_ptr<render::Renderer> r;
  if (!r) {
    std::string error;
    g_context = render::OffscreenContext::create(&error);
    if (!g_context) ADD_FAILURE() << error;
    r = render::Renderer::create(g_context->get_proc_address(), kWidth, kHeight, &error);
    if (!r) ADD_FAILURE() << error;
  }
  return *r;
}

test::RgbImage render_state(const Simulation& sim, const render::CaptureOptions& capture = {},
                            const render::DrawOptions& draw = {}) {
  render::Renderer& r = renderer();
  r.draw(render::capture_frame_state(sim, nullptr, capture), draw);
  std::vector<std::uint8_t> rgba;
  r.read_pixels(&rgba);
  return test::from_gl_pixels(rgba, r.width(), r.height());
}

void expect_golden(const Simulation& sim, const std::string& name,
                   const render::CaptureOptions& capture = {},
                   const render::DrawOptions& draw = {}) {
  const std::string message =
      test::check_golden(render_state(sim, capture, draw), name, ::invfree::test::golden_dir(),
                         ::invfree::test::golden_failure_dir());
  EXPECT_TRUE(message.empty()) << message;
}

SceneDef scene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  SceneDef s = *load_builtin_scene(name).scene;
  for (const auto& o : overrides) {
    const std::string e = apply_override(s, o);
    EXPECT_TRUE(e.empty()) << e;
  }
  return s;
}

void run_to(Simulation& sim, long step_count) {
  while (sim.step_count < step_count)
    ASSERT_EQ(step(sim).status, StepStatus::Ok) << "step " << sim.step_count + 1;
}

double ground_gap(const Simulation& sim) {
  double gap = INFINITY;
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    gap = std::min(gap, sim.x[2 * i + 1] - sim.scene.ground_y);
  return gap;
}

double min_det_f(const Simulation& sim) {
  const auto d = triangle_det_f(sim);
  return *std::min_element(d.begin(), d.end());
}

TEST(RenderGolden, CompressInitialState) {
  Simulation sim = make_simulation(scene("compress"));
  expect_golden(sim, "compress_t0");
}

TEST(RenderGolden, CompressFirstGroundContact) {
  // Step 32 is the first whose state has a node within the barrier's reach (d < dhat) of
  // the ground.
  constexpr long kContactStep = 32;
  Simulation sim = make_simulation(scene("compress"));
  run_to(sim, kContactStep - 1);
  EXPECT_GE(ground_gap(sim), sim.scene.dhat);
  run_to(sim, kContactStep);
  EXPECT_LT(ground_gap(sim), sim.scene.dhat);
  expect_golden(sim, "compress_first_contact");
}

TEST(RenderGolden, CompressMaximumCompression) {
  // The ceiling stops at step 260; det F keeps settling for a few dozen steps. Step 280:
  // ceiling at its stop and min det F within 0.5% of the smallest of the whole run.
  constexpr long kStep = 280;
  Simulation sim = make_simulation(scene("compress"));
  double smallest = 1.0, at_step = 0.0;
  while (sim.step_count < 300) {
    run_to(sim, sim.step_count + 1);
    smallest = std::min(smallest, min_det_f(sim));
    if (sim.step_count == kStep) {
      at_step = min_det_f(sim);
      EXPECT_LE(sim.ceiling_y, sim.scene.ceiling_stop + 1e-3);
      expect_golden(sim, "compress_max_compression");
    }
  }
  EXPECT_LE(at_step, smallest * 1.005);
}

// Issue 32 item 7: a failed run's last frame is marked in the picture. Symplectic Euler on
// compress penetrates the ground (the quickstart's third demonstration); the last good
// state is drawn with the failure, a red border and banner.
TEST(RenderGolden, CompressFailedRunIsMarked) {
  Simulation sim = make_simulation(scene("compress", {"solver.integrator=symplectic-euler"}));
  StepReport failure;
  while (sim.step_count < 300) {
    failure = step(sim);
    if (failure.status != StepStatus::Ok) break;
  }
  ASSERT_NE(failure.status, StepStatus::Ok) << "symplectic Euler did not fail";
  render::FrameState state = render::capture_frame_state(sim);
  state.failure = "step " + std::to_string(sim.step_count + 1) +
                  " failed: " + step_status_name(failure.status) + ": " + failure.message;
  render::Renderer& r = renderer();
  r.draw(state);
  std::vector<std::uint8_t> rgba;
  r.read_pixels(&rgba);
  const std::string message =
      test::check_golden(test::from_gl_pixels(rgba, r.width(), r.height()), "compress_failed",
                         ::invfree::test::golden_dir(), ::invfree::test::golden_failure_dir());
  EXPECT_TRUE(message.empty()) << message;
}

TEST(RenderGolden, DropAtRest) {
  constexpr long kStep = 400;
  Simulation sim = make_simulation(scene("drop"));
  run_to(sim, kStep);
  EXPECT_LT(sim.v.lpNorm<Eigen::Infinity>(), 1e-2);  // at rest on the ground
  EXPECT_LT(ground_gap(sim), sim.scene.dhat);
  expect_golden(sim, "drop_rest");
}

TEST(RenderGolden, LinearElasticityInverted) {
  // Linear elasticity allows det F <= 0: a soft square (E = 1e4) thrown onto the ground
  // at 8 m/s turns triangles near the ground inside out; they are drawn in the inverted
  // colour, on top of their neighbours.
  constexpr long kStep = 23;
  Simulation sim = make_simulation(scene("compress", {"material.model=linear", "material.E=1e4",
                                                      "mesh.n_seg=8", "initial.velocity=[0,-8]"}));
  run_to(sim, kStep);
  const auto det = triangle_det_f(sim);
  EXPECT_GT(std::count_if(det.begin(), det.end(), [](double d) { return d <= 0.0; }), 0);
  expect_golden(sim, "linear_inverted");
}

TEST(RenderGolden, InvertedTrianglesAreRinged) {
  // Rings mark every inverted triangle (and only those): with none, the option changes no
  // pixel; with some, it adds dark and green ring pixels around each.
  render::Renderer& r = renderer();
  const auto draw = [&](const Simulation& sim, bool rings) {
    render::DrawOptions o;
    o.ring_inverted = rings;
    r.draw(render::capture_frame_state(sim), o);
    std::vector<std::uint8_t> rgba;
    r.read_pixels(&rgba);
    return test::from_gl_pixels(rgba, r.width(), r.height());
  };
  Simulation sim = make_simulation(scene("compress", {"material.model=linear", "material.E=1e4",
                                                      "mesh.n_seg=8", "initial.velocity=[0,-8]"}));
  EXPECT_EQ(test::compare_images(draw(sim, true), draw(sim, false)).differing, 0);
  run_to(sim, 23);
  const test::ImageDiff d = test::compare_images(draw(sim, true), draw(sim, false));
  EXPECT_GT(d.differing, 2000);
}

TEST(RenderGolden, CompressFineMeshFoldsWithoutLoops) {
  // n_seg 64 at step 290 (the ceiling at its stop): the bottom surface folds in two places;
  // with self-contact the folds are creases, without it they are small loops through the
  // surface. The state is checked intersection-free by the exact test.
  constexpr long kStep = 290;
  Simulation sim =
      make_simulation(scene("compress", {"mesh.n_seg=64", "self_contact.enabled=true"}));
  run_to(sim, kStep);
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> scratch;
  EXPECT_FALSE(find_self_intersection(find_boundary(sim.mesh), sim.x, grid, scratch));
  EXPECT_LT(min_self_gap(sim), sim.scene.dhat);  // the fold's faces are in contact
  expect_golden(sim, "compress_fold_n64");
}

// The colourings of issue 26 (app/field_colormap.h), each on the state that tells its
// story; the legend's title, unit, ticks and markers are part of the picture.
render::CaptureOptions colored_by(TriangleField field, bool glyphs = false) {
  render::CaptureOptions c;
  c.color_by = field;
  c.stress_glyphs = glyphs;
  return c;
}

std::vector<double> field_of(const Simulation& sim, TriangleField field) {
  std::vector<double> v;
  triangle_field(sim, field, &v);
  return v;
}

TEST(RenderGolden, CompressPsiAtMaximumCompression) {
  // n_seg 8 squashed to the ceiling's stop: the energy density spans more than a decade,
  // highest in the middle of the contact and lowest at the bulging sides; the log scale
  // grades the whole body instead of showing one hot spot on a pale square.
  Simulation sim = make_simulation(scene("compress", {"mesh.n_seg=8"}));
  run_to(sim, 280);
  const auto psi = field_of(sim, TriangleField::Psi);
  const auto [lo, hi] = std::minmax_element(psi.begin(), psi.end());
  EXPECT_GT(*hi / *lo, 10.0);
  expect_golden(sim, "compress_psi", colored_by(TriangleField::Psi));
}

TEST(RenderGolden, CompressStressAtMaximumCompression) {
  // n_seg 8 squashed: compression (blue) through the body between the plates, strongest
  // at the ends of the ground contact, and tension (red) along the top under the ceiling.
  Simulation sim = make_simulation(scene("compress", {"mesh.n_seg=8"}));
  run_to(sim, 280);
  const auto stress = field_of(sim, TriangleField::Stress);
  EXPECT_LT(*std::min_element(stress.begin(), stress.end()), 0.0);
  EXPECT_GT(*std::max_element(stress.begin(), stress.end()), 0.0);
  expect_golden(sim, "compress_stress", colored_by(TriangleField::Stress));
}

TEST(RenderGolden, ClampedWhereNewtonsHessianDeparts) {
  // n_seg 8 at step 70 (det F within 2% of 1): neo-Hookean's twist eigenvalue is negative
  // exactly where det F < 1, so the projection clamps one eigenvalue there (orange) and
  // none where det F >= 1 (white: Newton's Hessian is the true one); both are on it.
  Simulation sim = make_simulation(scene("compress", {"mesh.n_seg=8"}));
  run_to(sim, 70);
  const auto clamped = field_of(sim, TriangleField::Clamped);
  EXPECT_GT(std::count(clamped.begin(), clamped.end(), 0.0), 10);
  EXPECT_GT(std::count(clamped.begin(), clamped.end(), 1.0), 10);
  expect_golden(sim, "compress_clamped", colored_by(TriangleField::Clamped));
}

TEST(RenderGolden, StressGlyphsOnACoarseMesh) {
  // The default mesh half squashed, coloured by stress: a cross per triangle, its vertical
  // stroke (the compression between the plates, blue) the longer.
  Simulation sim = make_simulation(scene("compress"));
  run_to(sim, 200);
  render::DrawOptions draw;
  draw.stress_glyphs = true;
  expect_golden(sim, "compress_stress_glyphs", colored_by(TriangleField::Stress, true), draw);
}

TEST(RenderGolden, StressGlyphsThinnedOnAFineMesh) {
  // n_seg 16 nearly squashed, over the det F colours: triangles smaller than a glyph cell,
  // so one glyph per cell; vertical compression between the plates, horizontal tension
  // along the top under the ceiling. (Edges off, as `render` leaves them where too dense.)
  Simulation sim = make_simulation(scene("compress", {"mesh.n_seg=16"}));
  run_to(sim, 250);
  render::DrawOptions draw;
  draw.stress_glyphs = true;
  draw.edges = false;
  expect_golden(sim, "compress_glyphs_thinned", colored_by(TriangleField::DetF, true), draw);
}

TEST(RenderGolden, SelectedTriangleIsOutlined) {
  // The inspector's triangle: a dark and yellow outline over the fills and the mesh, here
  // on Psi's colours (whose low end is a pale yellow).
  Simulation sim = make_simulation(scene("compress"));
  run_to(sim, 150);
  render::DrawOptions draw;
  draw.selected_triangle = 5;
  expect_golden(sim, "compress_selected", colored_by(TriangleField::Psi), draw);
  // Out of range: nothing outlined, the same pixels as no selection.
  draw.selected_triangle = sim.mesh.triangle_count();
  EXPECT_EQ(render_state(sim, colored_by(TriangleField::Psi), draw).rgb,
            render_state(sim, colored_by(TriangleField::Psi)).rgb);
}

TEST(RenderGolden, InvertedTrianglesAreRingedInEveryColouring) {
  // The rings mark det F <= 0 whatever fills the triangles (their fill is the field's).
  Simulation sim = make_simulation(scene("compress", {"material.model=linear", "material.E=1e4",
                                                      "mesh.n_seg=8", "initial.velocity=[0,-8]"}));
  run_to(sim, 23);
  for (const TriangleField field :
       {TriangleField::Psi, TriangleField::Stress, TriangleField::Clamped}) {
    render::DrawOptions no_rings;
    no_rings.ring_inverted = false;
    const test::ImageDiff d = test::compare_images(render_state(sim, colored_by(field)),
                                                   render_state(sim, colored_by(field), no_rings));
    EXPECT_GT(d.differing, 2000) << enum_name(kTriangleFieldNames, field);
  }
}

TEST(RenderGolden, MassSpringScenesHaveNoStressToDraw) {
  // The course's springs have no stress per triangle: no glyph data, the fields are 0, and
  // asking for glyphs changes no pixel.
  Simulation sim = make_simulation(scene("course-1-mass-spring"));
  run_to(sim, 20);
  const render::FrameState f =
      render::capture_frame_state(sim, nullptr, colored_by(TriangleField::Stress, true));
  EXPECT_TRUE(f.principal_stress.empty());
  EXPECT_EQ(f.field, std::vector<double>(sim.mesh.triangles.size(), 0.0));
  render::DrawOptions glyphs;
  glyphs.stress_glyphs = true;
  EXPECT_EQ(render_state(sim, colored_by(TriangleField::Stress, true), glyphs).rgb,
            render_state(sim, colored_by(TriangleField::Stress)).rgb);
}

// The shapes of issue 27, framed by their own extent (app/body_extent.h).
TEST(RenderGolden, RingSquashedToTheStop) {
  // The O-ring with the ceiling at its stop (step 250): flattened, the hole squeezed to a
  // slit; intersection-free by the exact test, every triangle det F > 0, nothing cut off.
  Simulation sim = make_simulation(scene("ring"));
  run_to(sim, 250);
  EXPECT_LE(sim.ceiling_y, sim.scene.ceiling_stop + 1e-3);
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> scratch;
  EXPECT_FALSE(find_self_intersection(find_boundary(sim.mesh), sim.x, grid, scratch));
  EXPECT_GT(min_det_f(sim), 0.0);
  expect_golden(sim, "ring_squashed");
}

TEST(RenderGolden, PlateHoleStressConcentration) {
  // The plate pulled at both ends, settled (step 100): the largest principal stress at the
  // hole's top and bottom edges is about three times the far field (Kirsch); the camera
  // shows the whole 2 m plate.
  Simulation sim = make_simulation(scene("plate-hole"));
  run_to(sim, 100);
  const auto stress = field_of(sim, TriangleField::Stress);
  const auto at = [&](double x, double y) {
    const std::optional<int> t = triangle_at(sim, Vec2(x, y));
    EXPECT_TRUE(t.has_value()) << x << ", " << y;
    return t ? stress[static_cast<size_t>(*t)] : 0.0;
  };
  const double far = at(0.0, 0.45), top = at(0.0, 0.165), bottom = at(0.0, -0.165);
  EXPECT_GT(far, 0.0);
  EXPECT_GT(top, 2.0 * far);
  EXPECT_GT(bottom, 2.0 * far);
  expect_golden(sim, "plate_hole_stress", colored_by(TriangleField::Stress));
}

// Overlays (renderer.h's Overlay): particles and springs of a mesh without triangles
// (the course's chapter 0), the affine basis's anchor triangle (chapter 9).

test::RgbImage render_frame(const render::FrameState& f, const render::DrawOptions& draw = {}) {
  render::Renderer& r = renderer();
  r.draw(f, draw);
  std::vector<std::uint8_t> rgba;
  r.read_pixels(&rgba);
  return test::from_gl_pixels(rgba, r.width(), r.height());
}

std::array<int, 3> pixel(const test::RgbImage& im, Vec2 p) {
  const size_t k = 3 * (static_cast<size_t>(std::lround(p.y())) * im.width +
                        static_cast<size_t>(std::lround(p.x())));
  return {im.rgb[k], im.rgb[k + 1], im.rgb[k + 2]};
}

// Within 12/255 of `c` in every channel.
bool near_color(const std::array<int, 3>& p, Rgb c) {
  const int want[3] = {int(std::lround(255 * c.r)), int(std::lround(255 * c.g)),
                       int(std::lround(255 * c.b))};
  for (int k = 0; k < 3; ++k)
    if (std::abs(p[k] - want[k]) > 12) return false;
  return true;
}

// A thin antialiased stroke may cover no pixel whole: some pixel within one of `p` is at
// least half way from the plot's background to `c` in every channel.
bool stroked(const test::RgbImage& im, Vec2 p, Rgb c) {
  const float bg[3] = {render::kPlotBackground.r, render::kPlotBackground.g,
                       render::kPlotBackground.b};
  const float want[3] = {c.r, c.g, c.b};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const std::array<int, 3> q = pixel(im, p + Vec2(dx, dy));
      bool half_way = true;
      for (int k = 0; k < 3; ++k)
        half_way = half_way &&
                   std::abs(q[k] / 255.0f - want[k]) <= 0.5f * std::abs(bg[k] - want[k]) + 0.02f;
      if (half_way) return true;
    }
  return false;
}

// A points body's simulation, made by hand until the course's chapter 0 scenes land: the
// mass-spring square of course-2-dirichlet hanging for 40 steps, then its triangles taken
// away, so that only its nodes and springs remain.
Simulation hanging_particles() {
  SceneDef s = scene("course-2-dirichlet");
  Simulation sim = make_simulation(s);
  run_to(sim, 40);
  sim.scene.shape.kind = ShapeKind::Points;
  sim.scene.shape.points = sim.mesh.rest;
  sim.mesh.triangles.clear();
  sim.mesh.rest_area.clear();
  sim.mesh.rest_shape_inverse.clear();
  return sim;
}

TEST(RenderGolden, ParticlesAndSpringsOfAMeshWithoutTriangles) {
  const Simulation sim = hanging_particles();
  const render::FrameState f = render::capture_frame_state(sim);
  ASSERT_EQ(f.overlays.size(), 1u);
  const render::Overlay& o = f.overlays[0];
  EXPECT_EQ(o.points.size(), size_t(sim.mesh.node_count()));
  EXPECT_EQ(o.segments.size(), sim.workspace->springs.size());
  EXPECT_NEAR(o.dot_radius, 0.025, 1e-12);  // a tenth of the 0.25 m spacing
  const test::RgbImage im = render_frame(f);
  // Every particle is a blue dot, in the plot.
  const render::Camera cam = renderer().camera(f.scene);
  for (const Vec2& p : o.points) {
    const Vec2 px = cam.to_pixel(p);
    ASSERT_GT(px.x(), 0.0);
    ASSERT_LT(px.x(), renderer().layout().plot.w);
    EXPECT_TRUE(near_color(pixel(im, px), render::kParticleColor)) << p.transpose();
  }
  // The middle of a spring is stroked.
  const auto [a, b] = o.segments.front();
  EXPECT_TRUE(stroked(im, cam.to_pixel(0.5 * (o.points[a] + o.points[b])), render::kParticleColor));
  expect_golden(sim, "particles_hanging");
}

TEST(RenderGolden, LoneParticleIsFramed) {
  // One particle: a rest box of no size. The camera still frames it (kParticleReach around
  // it), and the dot has the tutorial's 0.1 m radius.
  render::FrameState f;
  f.scene.name = "one particle";
  f.scene.has_ground = false;
  f.scene.has_ceiling = false;
  f.scene.has_gravity = false;  // (falling freely, it gets room below: see camera.h)
  f.scene.shape.kind = ShapeKind::Points;
  f.scene.shape.points = {Vec2(0.0, 0.0)};
  f.x = VecX::Zero(2);
  f.overlays.push_back(
      render::particle_overlay(f.x, {}, render::particle_dot_radius({Vec2(0, 0)}, {})));
  EXPECT_EQ(f.overlays[0].dot_radius, 0.1);
  const render::Camera cam = renderer().camera(f.scene);
  ASSERT_TRUE(std::isfinite(cam.pixels_per_metre));
  const Vec2 c = cam.to_pixel(Vec2(0, 0));
  const render::PixelRect plot = renderer().layout().plot;
  EXPECT_NEAR(c.x(), plot.x + 0.5 * plot.w, 1.0);
  EXPECT_NEAR(c.y(), plot.y + 0.5 * plot.h, 1.0);
  const test::RgbImage im = render_frame(f);
  const double r = 0.1 * cam.pixels_per_metre;
  EXPECT_GT(r, 20.0);
  EXPECT_TRUE(near_color(pixel(im, c), render::kParticleColor));
  EXPECT_TRUE(near_color(pixel(im, c + Vec2(r - 2.0, 0.0)), render::kParticleColor));
  EXPECT_FALSE(near_color(pixel(im, c + Vec2(r + 2.0, 0.0)), render::kParticleColor));
  // Under gravity, with nothing to hold it and no ground, the particle starts in the upper
  // part of the picture, room to fall below it.
  f.scene.has_gravity = true;
  const Vec2 falling = renderer().camera(f.scene).to_pixel(Vec2(0, 0));
  EXPECT_LT(falling.y(), plot.y + 0.35 * plot.h);
  EXPECT_GT(falling.y(), plot.y + 0.1 * plot.h);
}

TEST(RenderGolden, AnchorTriangleOverTheMesh) {
  // The affine basis's anchor triangle, drawn from a hand-made frame (core gives it once the
  // reduced solve lands): red strokes and corner dots over the triangles and their edges,
  // under the selected triangle's outline.
  Simulation sim = make_simulation(scene("compress"));
  render::FrameState f = render::capture_frame_state(sim);
  EXPECT_TRUE(f.overlays.empty());  // a full-space scene: none
  const std::array<Vec2, 3> corners = {Vec2(-0.4, -0.35), Vec2(0.45, -0.35), Vec2(-0.4, 0.4)};
  f.overlays.push_back(render::anchor_overlay(corners, 0.25));
  render::DrawOptions draw;
  draw.selected_triangle = 0;
  const test::RgbImage im = render_frame(f, draw);
  const render::Camera cam = renderer().camera(f.scene);
  for (const Vec2& p : corners)
    EXPECT_TRUE(near_color(pixel(im, cam.to_pixel(p)), render::kAnchorColor)) << p.transpose();
  for (int k = 0; k < 3; ++k)
    EXPECT_TRUE(
        stroked(im, cam.to_pixel(0.5 * (corners[k] + corners[(k + 1) % 3])), render::kAnchorColor))
        << k;
  const std::string message =
      test::check_golden(im, "anchor_triangle", test::golden_dir(), test::golden_failure_dir());
  EXPECT_TRUE(message.empty()) << message;
  // Without the overlay the same frame has no red there.
  f.overlays.clear();
  const test::RgbImage plain = render_frame(f, draw);
  EXPECT_FALSE(near_color(pixel(plain, cam.to_pixel(corners[0])), render::kAnchorColor));
  EXPECT_EQ(plain.rgb, render_state(sim, {}, draw).rgb);
}

TEST(RenderGolden, AffineBasisDrawsItsAnchorTriangle) {
  // course-9-affine after its landing (step 40): the anchor triangle carried by the body's
  // affine map (core's affine_anchor_triangle), red over the mesh.
  Simulation sim = make_simulation(scene("course-9-affine"));
  run_to(sim, 40);
  const render::FrameState f = render::capture_frame_state(sim);
  ASSERT_EQ(f.overlays.size(), 1u);
  const auto anchors = affine_anchor_triangle(sim.scene, sim.mesh, sim.x);
  ASSERT_TRUE(anchors.has_value());
  const render::Overlay& o = f.overlays[0];
  ASSERT_EQ(o.points.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(o.points[k], (*anchors)[k]);
  const test::RgbImage im = render_frame(f);
  const render::Camera cam = renderer().camera(f.scene);
  for (const Vec2& p : o.points)
    EXPECT_TRUE(near_color(pixel(im, cam.to_pixel(p)), render::kAnchorColor)) << p.transpose();
  expect_golden(sim, "course_9_affine");
  // Other bases draw none.
  EXPECT_TRUE(
      render::capture_frame_state(make_simulation(scene("course-9-quadratic"))).overlays.empty());
}

TEST(RenderGolden, SameStateSamePixels) {
  // Nothing in the picture depends on the wall clock or on what was drawn before.
  Simulation a = make_simulation(scene("compress"));
  run_to(a, 40);
  const test::RgbImage first = render_state(a);
  Simulation other = make_simulation(scene("drop"));
  render_state(other);
  const test::RgbImage again = render_state(a);
  EXPECT_EQ(first.rgb, again.rgb);
}

TEST(RenderGolden, DrawsTheSameFrameIntoAGivenFramebuffer) {
  // DrawOptions::framebuffer, the live window's path: a framebuffer the caller owns
  // receives the very pixels the renderer's own would, and the renderer's own frame
  // (read_pixels) stays the one drawn before.
  render::Renderer& r = renderer();
  render::GlApi gl;
  ASSERT_EQ(render::load_gl_api(g_context->get_proc_address(), &gl), "");
  GLuint texture = 0, framebuffer = 0;
  gl.GenTextures(1, &texture);
  gl.BindTexture(GL_TEXTURE_2D, texture);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kWidth, kHeight, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.GenFramebuffers(1, &framebuffer);
  gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
  ASSERT_EQ(gl.CheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);

  Simulation compressed = make_simulation(scene("compress"));
  run_to(compressed, 150);
  const Simulation dropped = make_simulation(scene("drop"));
  const test::RgbImage own_before = render_state(compressed);
  render::DrawOptions into_given;
  into_given.framebuffer = framebuffer;
  r.draw(render::capture_frame_state(dropped), into_given);
  std::vector<std::uint8_t> given(static_cast<size_t>(kWidth) * kHeight * 4);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.ReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, given.data());
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  std::vector<std::uint8_t> own_after;
  r.read_pixels(&own_after);
  EXPECT_EQ(test::from_gl_pixels(own_after, kWidth, kHeight).rgb, own_before.rgb);

  const test::RgbImage own_dropped = render_state(dropped);
  EXPECT_NE(own_dropped.rgb, own_before.rgb);  // two different pictures
  EXPECT_EQ(test::from_gl_pixels(given, kWidth, kHeight).rgb, own_dropped.rgb);
  gl.DeleteFramebuffers(1, &framebuffer);
  gl.DeleteTextures(1, &texture);
}

}  // namespace
}  // namespace invfree
