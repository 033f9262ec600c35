// The live classroom window: a GLFW window showing the running simulation drawn by the
// shared renderer (app/render/renderer.h), with a Dear ImGui panel on the left to drive
// it (app/live/live_panel.h), keyboard shortcuts (app/live/key_bindings.h), mouse pan,
// zoom and node grabbing, a click that inspects a triangle (the Inspector window,
// app/live/inspector_panel.h), the energy landscape's window, screenshots and PNG-sequence
// recording.
//
// GL: one OpenGL 3.3 core context from GLFW (GLX). The renderer loads its functions with
// glfwGetProcAddress; ImGui draws with its OpenGL3 backend (the packaged one loads libGL
// itself), so this code calls no gl* function directly: it reads the window through the
// renderer's GlApi table as well.
//
// Input all goes through ImGui's io (mouse position and buttons, wheel, keys), so a test
// can inject it between the backend's NewFrame and ImGui::NewFrame (see Injection), and
// the panel and the scene see exactly what a person's mouse would do.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "app/live/live_controller.h"
#include "app/live/triangle_inspection.h"
#include "app/plot/chart.h"
#include "app/render/camera.h"
#include "app/render/view_choices.h"
#include "triangle_fields.h"

namespace invfree::live {

// The n_seg slider's maximum: the largest mesh that keeps the window at >= 30 frames/s on
// the project's 2-core machine, otherwise idle, under Xvfb, with the self-contact checkbox
// on (the default) as well as off (checked with `xvfb-run -a invfree live --frames 300
// --bench --set mesh.n_seg=N`, with and without `--set self_contact.enabled=false`). Larger meshes
// can still be loaded from a scene file or --set, or allowed with --max-n-seg.
constexpr int kDefaultMaxSegments = 104;

// The UI scale's range: the panel's text is 16 px times the scale, and the det F panel is
// its 1280x720 design times the scale.
constexpr float kMinUiScale = 0.75f, kMaxUiScale = 3.0f;

struct LiveOptions {
  std::vector<SceneChoice> scenes;  // the scene picker; not empty
  int selected = 0;
  int frames = 0;                    // > 0: run this many frames, then close
  std::string screenshot_file;       // write the last frame here (with frames > 0)
  std::string screenshot_dir = ".";  // Ctrl+P / the button: DIR/invfree_NNNN.png
  std::string record_dir;            // record from the first frame on
  bool record_force = false;         // record_dir may hold files (this run's replace them)
  bool bench = false;                // print frames/s at the end
  bool paused = false;               // start paused
  bool hide_panel = false;           // start with the panel hidden (Tab shows it)
  bool presentation = false;         // start in presentation mode (P leaves it)
  // Touch controls (the web page): a button opens and closes the panel, which starts closed
  // where it would leave the picture a strip (app/live/panel_layout.h).
  bool touch_controls = false;
  // 0: from the window (its content scale times its size over 1280x720, at least 1).
  float ui_scale = 0.0f;
  render::PanelMode det_f_panel = render::PanelMode::Side;
  // The projector's defaults (`invfree live` and the page choose them, docs/live.md):
  // these are the plain ones: the scene's mesh, the fixed scale, the stage.
  render::ColorRangeMode color_range = render::ColorRangeMode::Fixed;
  // Each scene's square meshed at least this fine (render::refine_for_projector; 0: the
  // scenes' own meshes), except the selected one's with keep_selected_mesh (its mesh set on
  // the command line, or --select-triangle naming inspect's triangle).
  int min_n_seg = 0;
  bool keep_selected_mesh = false;
  bool follow_camera = false;  // the camera follows the bodies (false: frames the stage)
  TriangleField color_by = TriangleField::DetF;  // what the triangles are coloured by
  bool stress_glyphs = false;
  bool show_landscape = false;  // the energy landscape's window
  int select_triangle = -1;     // >= 0: inspect this triangle from the start
  bool vsync = true;            // off for --frames and --bench
  int width = 1280, height = 720;
  int steps_per_frame = 1;
  int max_segments = kDefaultMaxSegments;
  // Multisampling of the picture; 0: 4x, or 1x on a software rasterizer named by
  // GL_RENDERER (a browser masks that name: the web page finds out itself).
  int samples = 0;
  std::function<bool()> stop;  // checked every frame: true ends the run (e.g. Ctrl-C)
};

// Input a test substitutes for the real one in a frame: the mouse (window pixels, y
// down) and keys held down during this frame (GLFW key codes; a key listed in one frame
// and not the next is one press).
struct Injection {
  float x = 0, y = 0;
  bool down[3] = {false, false, false};  // left, right, middle
  float wheel = 0;
  std::vector<int> keys;
  bool ctrl = false;
  std::string text;  // typed characters (ASCII)
};

// Screen rectangle of a panel widget in the last frame (window pixels).
struct WidgetRect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LiveAppImpl;

class LiveApp {
 public:
  // Opens the window. Returns null with a one-line *error when there is no display or no
  // usable OpenGL 3.3 (the message suggests `invfree render` and xvfb-run).
  static std::unique_ptr<LiveApp> create(const LiveOptions& options, std::string* error);
  ~LiveApp();
  LiveApp(const LiveApp&) = delete;
  LiveApp& operator=(const LiveApp&) = delete;

  // One displayed frame: input, the simulation's steps, drawing, swap. With `capture`,
  // the window as shown (panel included) is read back before the swap.
  void frame(const Injection* inject = nullptr, Image* capture = nullptr);
  bool should_close() const;
  long frames_drawn() const;

  LiveController& controller();
  // Window coordinates (ImGui's, y down) of a world point in the current view.
  Vec2 to_window(const Vec2& world) const;
  // Last frame's rectangle of a named widget ("mu", "lambda", "play", ...), if drawn.
  const std::map<std::string, WidgetRect>& widget_rects() const;
  // Messages printed for the user (screenshot paths, recording start/stop), also kept here.
  const std::vector<std::string>& messages() const;
  // The view's settings as the panel holds them (UI scale, det F panel, colour range).
  struct View {
    float ui_scale;
    render::PanelMode det_f_panel;
    render::ColorRangeMode color_range;
  };
  View view() const;
  // The inspector's values as last shown (this frame's state, before its steps), or null
  // with no triangle selected.
  const Inspected* inspected() const;
  // Selects triangle t (as a click on it does); -1 or an index off the mesh releases.
  void select_triangle(int t);
  // Left clicks on the picture that hit no triangle while none was selected (the web
  // page's tap there plays or pauses); a click that selects or releases is not counted.
  long empty_clicks() const;
  // CPU time (ms, the main thread's) spent so far on two parts of the frames: copying the
  // state for the picture with its colouring (capture_frame_state: det F, or the field the
  // triangles are coloured by, and the glyphs' stresses), and the inspector's and the
  // landscape's windows (the analysis, its finite differences, the ImGui drawing).
  struct PartTimes {
    double capture_ms = 0.0;
    double inspection_ms = 0.0;
  };
  PartTimes part_times() const;
  // What the panel's view section colours the triangles by (its combo, or this setter).
  TriangleField color_by() const;
  void set_color_by(TriangleField field);
  // Presentation mode (key P): full screen, no panel, large readouts.
  bool presenting() const;
  // Simulated seconds per real second while playing (real_time_rate.h), once measured.
  std::optional<double> real_time_rate() const;
  // The det F colour range's bounds gathered over the run (auto over the run), [lo, hi].
  std::pair<double, double> color_range_run() const;

 private:
  LiveApp();
  std::unique_ptr<LiveAppImpl> impl_;
};

// `invfree live`: runs the window until closed (or for options.frames frames), writes
// the screenshot, prints the benchmark line. Returns the process exit code.
int run_live(const LiveOptions& options);

// True when a window can plausibly be opened (DISPLAY or WAYLAND_DISPLAY is set).
bool display_available();

}  // namespace invfree::live
