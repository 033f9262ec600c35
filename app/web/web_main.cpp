// The web page's program (docs/web.md): `invfree live` (app/live/live_app.h) in the page's
// canvas, the built-in scenes in its picker. The browser calls page_frame once per
// animation frame (emscripten_set_main_loop); each call is one LiveApp::frame, the same
// body the desktop's loop runs.
//
// Inputs: the page's URL query: paused=1 starts paused (the tests' first frame),
// n_seg=N starts with that mesh (through the controller's checks: a value they refuse
// leaves the scene's mesh, and the panel's note says why), scene=NAME picks a built-in
// scene. The projector's defaults of `invfree live` (docs/live.md): a square
// coarser than 16 x 16 meshed at 16 (min_n_seg=0 keeps the scenes' meshes), the colour
// range of the run (color_range=fixed|run|frame), the camera on the bodies (camera=fixed:
// the whole stage).
// Touch (shell.html): a finger is the left mouse button; a short tap on a triangle inspects it
// (as a click does on the desktop), a tap on empty space releases the inspected one, or, with
// none inspected, plays or pauses.
// Outputs: the canvas, screenshots as downloads, and `window.invfree` after every frame (frames,
// steps, min det F, mu, lambda, n_seg, frames/s, the colouring, the triangle count, the
// inspected triangle's values as `selected`, the panel's widget rectangles, note, banner), read
// by the tests in a headless browser (tests/web) and by anyone curious in the browser's console.
// Module._invfree_triangle_window_x/y(t) give a triangle's centroid in the page's pixels (for a
// test's tap); Module._invfree_mesh_ms(repeats) times CGAL's mesher on the current scene's
// shapes in the page (issue 27).
#include <GLFW/glfw3.h>
#include <emscripten.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "app/live/course.h"
#include "app/live/live_app.h"
#include "app/live/step_time.h"
#include "app/render/projector_mesh.h"
#include "linalg/parallel.h"
#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "shape/shape_region.h"
#include "shape/triangulate.h"
#include "triangle_fields.h"

namespace {

using invfree::live::LiveApp;

// The n_seg slider's maximum in the page: the largest mesh that holds about 30 frames/s in
// headless Chromium on a 2-core machine (docs/web.md, "Speed", gives the figures and
// `tests/web/measure_fps.py` measures them). Larger meshes can still be asked for in the
// URL (?n_seg=N).
constexpr int kWebMaxSegments = 40;

struct Page {
  std::unique_ptr<LiveApp> app;
  bool failed = false;
  size_t messages_seen = 0;
  // Frames left in which a short tap (shell.html) may still turn out a click on empty space
  // with nothing inspected (ImGui sees its release a frame or two after the tap's events),
  // and the count of such clicks when it came.
  int tap_frames = 0;
  long empty_clicks_at_tap = 0;
  // frames/s over the last second, for window.invfree
  double fps_start_ms = 0.0, fps = 0.0;
  long fps_frames = 0;
};

int query_int(const char* key, int fallback) {
  // clang-format off
  return EM_ASM_INT({
    const v = new URLSearchParams(window.location.search).get(UTF8ToString($0));
    if (v === null || v === "" || !/^-?[0-9]+$/.test(v)) return $1;
    return parseInt(v, 10);
  }, key, fallback);
  // clang-format on
}

std::string query_string(const char* key) {
  char buffer[64] = {};
  // clang-format off
  EM_ASM({
    const v = new URLSearchParams(window.location.search).get(UTF8ToString($0)) || "";
    stringToUTF8(v, $1, $2);
  }, key, buffer, static_cast<int>(sizeof buffer));
  // clang-format on
  return buffer;
}

int window_width() {
  return EM_ASM_INT({ return window.innerWidth; });
}
int window_height() {
  return EM_ASM_INT({ return window.innerHeight; });
}

// True when WebGL is drawn by a CPU rasterizer (headless Chromium's SwiftShader, Mesa's
// llvmpipe): multisampling would then cost a large part of each frame, as on the desktop
// (LiveApp::create). The browser masks GL_RENDERER; the debug extension names it.
bool software_webgl() {
  // clang-format off
  return EM_ASM_INT({
    const gl = document.createElement("canvas").getContext("webgl2");
    const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
    const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
    const lose = gl && gl.getExtension("WEBGL_lose_context");
    if (lose) lose.loseContext();  // this probe's context is not needed any more
    return /SwiftShader|llvmpipe|softpipe/i.test(name) ? 1 : 0;
  });
  // clang-format on
}

void show_error(const std::string& message) {
  std::fprintf(stderr, "invfree: %s\n", message.c_str());
  // clang-format off
  EM_ASM({
    const status = document.getElementById("status");
    if (status) { status.textContent = UTF8ToString($0); status.style.display = "block"; }
  }, message.c_str());
  // clang-format on
}

std::unique_ptr<LiveApp> open_app() {
  invfree::live::LiveOptions o;
  // The picker in the desktop's order (app/live_command.cpp): the course's scenes first,
  // in chapter order, then the others; `compress` is shown first, as `invfree live` does.
  std::vector<std::string> names;
  for (const auto& e : invfree::builtin_scenes()) names.emplace_back(e.name);
  invfree::live::put_course_first(names);
  for (const std::string& name : names) {
    const invfree::SceneLoad loaded = invfree::load_builtin_scene(name);
    if (loaded.scene) o.scenes.push_back({name, *loaded.scene});
  }
  std::string scene = query_string("scene");
  if (scene.empty()) scene = "compress";
  for (size_t i = 0; i < o.scenes.size(); ++i)
    if (o.scenes[i].label == scene) o.selected = static_cast<int>(i);
  o.paused = query_int("paused", 0) != 0;
  o.min_n_seg = std::max(0, query_int("min_n_seg", invfree::render::kProjectorMinSegments));
  const std::string range = query_string("color_range");
  o.color_range = invfree::render::parse_color_range_mode(range.empty() ? "run" : range)
                      .value_or(invfree::render::ColorRangeMode::Run);
  o.follow_camera = query_string("camera") != "fixed";
  o.max_segments = kWebMaxSegments;
  o.touch_controls = true;  // a phone has no Tab key: the panel opens and closes by a button
  if (software_webgl()) o.samples = 1;
  o.width = std::max(320, window_width());
  o.height = std::max(240, window_height());
  std::string error;
  auto app = LiveApp::create(o, &error);
  if (!app) {
    show_error(error);
    return nullptr;
  }
  if (const int n_seg = query_int("n_seg", 0); n_seg != 0) {
    invfree::live::LiveController& lc = app->controller();
    invfree::SceneDef next = lc.settings();
    next.n_seg = n_seg;
    if (!lc.apply(next)) std::printf("invfree: n_seg=%d: %s\n", n_seg, lc.note.c_str());
  }
  return app;
}

// The canvas fills the browser window: follow its size (GLFW's window is the canvas).
void follow_browser_window() {
  GLFWwindow* window = glfwGetCurrentContext();
  if (!window) return;
  int w = 0, h = 0;
  glfwGetWindowSize(window, &w, &h);
  const int want_w = std::max(320, window_width()), want_h = std::max(240, window_height());
  if (w != want_w || h != want_h) glfwSetWindowSize(window, want_w, want_h);
}

// A number for JSON (which has no inf or nan: null).
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The inspected triangle as JSON: null, or its index, the step, J, psi, the singular values,
// the four eigenvalues of dP/dF before and after the projection, and how many it clamped
// (for a mass-spring scene only the index and "elastic":false).
std::string selected_json(const LiveApp& app) {
  const invfree::live::Inspected* in = app.inspected();
  if (!in) return "null";
  std::string j = "{\"triangle\":" + std::to_string(in->triangle) +
                  ",\"step\":" + std::to_string(in->step) +
                  ",\"elastic\":" + (in->elastic ? "true" : "false");
  if (in->elastic) {
    const invfree::StressAnalysis& a = in->analysis;
    const auto list = [](auto v) {
      std::string l = "[";
      for (int k = 0; k < v.size(); ++k) l += (k ? "," : "") + json_number(v(k));
      return l + "]";
    };
    j += ",\"J\":" + json_number(a.J) + ",\"psi\":" + json_number(a.psi) +
         ",\"sigma\":" + list(a.svd.sigma) + ",\"eigenvalues\":" + list(a.eigenvalues) +
         ",\"projected_eigenvalues\":" + list(a.projected_eigenvalues) +
         ",\"clamped\":" + std::to_string(a.clamped) +
         ",\"finite\":" + (a.finite ? "true" : "false");
  }
  return j + "}";
}

void publish_state(Page& p) {
  const invfree::live::LiveController& lc = p.app->controller();
  const double now = emscripten_get_now();
  ++p.fps_frames;
  if (now - p.fps_start_ms >= 1000.0) {
    p.fps = p.fps_start_ms > 0.0 ? 1000.0 * p.fps_frames / (now - p.fps_start_ms) : 0.0;
    p.fps_start_ms = now;
    p.fps_frames = 0;
  }
  std::string widgets;
  for (const auto& [name, r] : p.app->widget_rects()) {
    char item[160];
    std::snprintf(item, sizeof item, "%s\"%s\":[%.1f,%.1f,%.1f,%.1f]", widgets.empty() ? "" : ",",
                  name.c_str(), r.x0, r.y0, r.x1, r.y1);
    widgets += item;
  }
  const invfree::SceneDef& s = lc.settings();
  const long steps = lc.steps_total();
  char head[512];
  std::snprintf(head, sizeof head,
                "{\"frames\":%ld,\"steps\":%ld,\"min_det_f\":%.17g,\"mu\":%.17g,\"lambda\":%.17g,"
                "\"n_seg\":%d,\"playing\":%s,\"fps\":%.2f,\"step_ms\":%.6g,\"scene\":\"%s\","
                "\"color_by\":\"%s\",\"triangles\":%d,\"step_time\":\"%s\",",
                p.app->frames_drawn(), steps, lc.stats().min_det_f, s.lame.mu, s.lame.lambda,
                s.n_seg, lc.playing() ? "true" : "false", p.fps,
                steps ? lc.step_ms_total() / steps : 0.0, s.name.c_str(),
                invfree::enum_name(invfree::kTriangleFieldNames, p.app->color_by()),
                lc.simulation().mesh.triangle_count(),
                lc.has_stepped() ? invfree::live::step_time_text(
                                       invfree::live::shown_step_ms(lc.ms_history().values(),
                                                                    lc.last_report().wall_ms))
                                       .c_str()
                                 : "");
  const std::string json = head + std::string("\"selected\":") + selected_json(*p.app) +
                           ",\"widgets\":{" + widgets + "}}";
  // note and banner are free text: handed over as strings, not spliced into the JSON.
  // clang-format off
  EM_ASM({
    const state = JSON.parse(UTF8ToString($0));
    state.note = UTF8ToString($1);
    state.banner = UTF8ToString($2);
    window.invfree = state;
  }, json.c_str(), lc.note.c_str(), lc.banner.c_str());
  // clang-format on
}

// The panel's Screenshot button (and Ctrl+P) writes a PNG into the page's in-memory file
// system and says "screenshot: PATH"; the browser then downloads that file.
void download_screenshots(Page& p) {
  const auto& messages = p.app->messages();
  const std::string prefix = "screenshot: ";
  for (; p.messages_seen < messages.size(); ++p.messages_seen) {
    const std::string& m = messages[p.messages_seen];
    if (m.compare(0, prefix.size(), prefix) != 0) continue;
    // clang-format off
    EM_ASM({
      const path = UTF8ToString($0);
      const bytes = FS.readFile(path);
      FS.unlink(path);
      const link = document.createElement("a");
      link.href = URL.createObjectURL(new Blob([bytes], {type: "image/png"}));
      link.download = path.split("/").pop();
      document.body.appendChild(link);
      link.click();
      link.remove();
      setTimeout(() => URL.revokeObjectURL(link.href), 10000);
    }, m.c_str() + prefix.size());
    // clang-format on
  }
}

// One animation frame. The app is opened in the first one, once the main loop exists
// (GLFW's swap interval sets the main loop's timing, which needs a main loop).
void page_frame(void* arg) {
  Page& p = *static_cast<Page*>(arg);
  if (p.failed) return;
  if (!p.app) {
    p.app = open_app();
    if (!p.app) {
      p.failed = true;
      emscripten_cancel_main_loop();
      return;
    }
    EM_ASM({
      const status = document.getElementById("status");
      if (status) status.style.display = "none";
    });
  }
  follow_browser_window();
  p.app->frame();
  // A tap is also a click (the touch's mouse events): on a triangle it inspects it, on
  // empty space it releases the inspected one, on the panel it is the panel's; only a tap
  // on empty space with nothing inspected plays or pauses. Decided after the frames in
  // which ImGui sees the release: a slow frame can bring the touch's move, press and
  // release all at once, and ImGui takes the press in one frame and the release in the next.
  if (p.tap_frames > 0) {
    if (p.app->empty_clicks() > p.empty_clicks_at_tap) {
      invfree::live::LiveController& lc = p.app->controller();
      lc.set_playing(!lc.playing());
      p.tap_frames = 0;
    } else {
      --p.tap_frames;
    }
  }
  download_screenshots(p);
  publish_state(p);
}

Page g_page;

}  // namespace

// Called by the page's touch handling (shell.html) after a short tap.
extern "C" EMSCRIPTEN_KEEPALIVE void invfree_tap() {
  g_page.tap_frames = 3;
  g_page.empty_clicks_at_tap = g_page.app ? g_page.app->empty_clicks() : 0;
}

// Triangle t's centroid in the page's pixels (the canvas's window coordinates), NaN when t
// is not a triangle of the mesh: where a test taps to inspect it.
static double triangle_window_coordinate(int t, int axis) {
  if (!g_page.app) return NAN;
  const invfree::Simulation& sim = g_page.app->controller().simulation();
  if (t < 0 || t >= sim.mesh.triangle_count()) return NAN;
  invfree::Vec2 c = invfree::Vec2::Zero();
  for (int node : sim.mesh.triangles[static_cast<size_t>(t)]) c += sim.x.segment<2>(2 * node);
  return g_page.app->to_window(c / 3.0)(axis);
}
extern "C" EMSCRIPTEN_KEEPALIVE double invfree_triangle_window_x(int t) {
  return triangle_window_coordinate(t, 0);
}
extern "C" EMSCRIPTEN_KEEPALIVE double invfree_triangle_window_y(int t) {
  return triangle_window_coordinate(t, 1);
}

// Meshing time in the page (issue 27: CGAL's mesher runs in WebAssembly): each meshed
// body of the current scene at its n_seg, region and triangulation (shape/shape_region.h,
// shape/triangulate.h, what mesh_shape does, without its cache), `repeats` times. Returns
// the milliseconds of one meshing of all of them (the median), -1 when no body is meshed
// or meshing fails; invfree_mesh_triangles() then gives their triangle count. For
// tests/web/measure_fps.py --scene and the web test's ring case.
static long g_mesh_triangles = 0;
extern "C" EMSCRIPTEN_KEEPALIVE double invfree_mesh_ms(int repeats) {
  g_mesh_triangles = 0;
  if (!g_page.app) return -1;
  const invfree::SceneDef& scene = g_page.app->controller().simulation().scene;
  std::vector<double> times;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    long triangles = 0;
    const double start = emscripten_get_now();
    for (int b = 0; b < invfree::body_count(scene); ++b) {
      const invfree::PlacedBody body = invfree::placed_body(scene, b);
      if (body.shape.kind == invfree::ShapeKind::Square ||
          body.shape.kind == invfree::ShapeKind::MeshFile ||
          body.shape.kind == invfree::ShapeKind::Points)  // particles: not meshed
        continue;
      const double max_edge = invfree::shape_max_edge(body.shape, body.n_seg);
      const invfree::ShapeRegion region = invfree::shape_region(body.shape, max_edge);
      if (!region.error.empty()) return -1;
      const invfree::Triangulation t =
          invfree::triangulate_region(region.loops, max_edge, 10'000'000);
      if (!t.error.empty()) return -1;
      triangles += static_cast<long>(t.triangles.size());
    }
    times.push_back(emscripten_get_now() - start);
    if (triangles == 0) return -1;
    g_mesh_triangles = triangles;
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}
extern "C" EMSCRIPTEN_KEEPALIVE double invfree_mesh_triangles() {
  return static_cast<double>(g_mesh_triangles);
}

int main() {
  // The page has no threads (no -pthread: that would need cross-origin isolation headers
  // from the server); the core's thread pool then runs everything on the calling thread.
  invfree::set_thread_count(1);
  emscripten_set_main_loop_arg(page_frame, &g_page, 0, 1);
  return 0;
}
