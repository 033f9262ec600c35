#include "app/live/live_app.h"

#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>

#include "app/exit_codes.h"
#include "app/live/key_bindings.h"
#include "app/live/live_panel.h"
#include "app/live/output_naming.h"
#include "app/live/view_transform.h"
#include "app/output_files.h"
#include "app/render/frame_writer.h"
#include "app/render/gl_api.h"
#include "app/render/renderer.h"

// The DejaVu Sans file embedded by app/plot/font.cpp (the chart font): ImGui's text uses
// the same face as the rendered frames, with no run-time font lookup.
extern "C" const unsigned char invfree_chart_font_begin[];
extern "C" const unsigned char invfree_chart_font_end[];

namespace invfree::live {

namespace {

std::string g_glfw_error;  // the last GLFW error, for one-line messages

void on_glfw_error(int, const char* description) {
  g_glfw_error = description ? description : "unknown error";
}

// GLFW is process-wide: initialised by the first window and left so until the process
// exits. glfwTerminate would unload libGL and Mesa's driver, and the allocations they
// still hold would become unreachable (LeakSanitizer reports them under the sanitize
// preset); the system reclaims all of it at exit anyway.
bool g_glfw_initialized = false;

// Set by the GLFW input callbacks below (ImGui's backend chains them): the live window's
// idle wait ends on any input.
bool g_input_seen = false;
void note_input() {
  g_input_seen = true;
}
void on_key(GLFWwindow*, int, int, int, int) {
  note_input();
}
void on_char(GLFWwindow*, unsigned) {
  note_input();
}
void on_cursor(GLFWwindow*, double, double) {
  note_input();
}
void on_button(GLFWwindow*, int, int, int) {
  note_input();
}
void on_scroll(GLFWwindow*, double, double) {
  note_input();
}
void on_size(GLFWwindow*, int, int) {
  note_input();
}
void on_focus(GLFWwindow*, int) {
  note_input();
}
void on_enter(GLFWwindow*, int) {
  note_input();
}
void on_refresh(GLFWwindow*) {  // the window was uncovered: draw it again
  note_input();
}

constexpr float kFontSize = 16.0f, kBigFontSize = 40.0f;  // at UI scale 1
constexpr double kGrabRadiusPixels = 14.0;
// While paused and idle the window waits for input this long at most (so that Ctrl-C and
// --frames still end it): no frame is drawn when nothing changes.
constexpr double kIdleWaitSeconds = 0.25;
constexpr int kPngCompression = 1;  // fastest zlib level: recording keeps up with the window

std::string no_window_message(const std::string& reason) {
  return "cannot open the live window (" + reason +
         "); for pictures without a display use `invfree render`, or run `xvfb-run -a invfree live "
         "...`";
}

// Flips GL's bottom-up RGBA rows into an Image (top row first).
Image image_from_bottom_up(const std::vector<std::uint8_t>& rgba, int w, int h) {
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.resize(rgba.size());
  const size_t row = static_cast<size_t>(w) * 4;
  for (int y = 0; y < h; ++y)
    std::copy(rgba.begin() + static_cast<long>((h - 1 - y) * row),
              rgba.begin() + static_cast<long>((h - y) * row),
              img.rgba.begin() + static_cast<long>(y * row));
  return img;
}

}  // namespace

bool display_available() {
#ifdef __EMSCRIPTEN__
  return true;  // the browser's canvas
#else
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
#endif
}

struct LiveAppImpl {
  LiveOptions options;
  GLFWwindow* window = nullptr;
  bool imgui_glfw = false, imgui_gl = false;
  render::GlApi gl;
  std::unique_ptr<render::Renderer> renderer;
  std::unique_ptr<LiveController> controller;
  PanelState panel;
  ViewTransform view;
  bool auto_fit = true;     // refit on resize / panel toggle until the user pans or zooms
  bool fit_bodies = false;  // the last fit framed the bodies (F), not the whole stage
  int fit_scene_index = -1, fit_n_seg = -1;
  // Mouse gestures in progress.
  enum class Drag { None, Pan, Pull } drag = Drag::None;
  Vec2 last_mouse = Vec2::Zero();
  // Outputs.
  std::unique_ptr<render::FrameWriter> recorder;
  OutputDirectory record_output;  // the recording's directory, locked while recording
  std::string record_dir;
  long record_frame = 0;
  std::vector<std::string> messages;
  long frames = 0;
  // The view: the UI scale the fonts were built at, the det F colour range over the run.
  float applied_ui_scale = 0.0f;
  ImGuiStyle base_style;
  render::ColorRangeTracker color_range;
  // The pointer: hover highlights only once it has moved (a still pointer under Xvfb
  // would ring whatever node lies under it in every scripted screenshot).
  bool pointer_moved = false;
  bool pointer_seen = false;
  ImVec2 pointer_start;
  // Input arrived (GLFW callbacks, chained by ImGui's): frames to draw before idling.
  int busy_frames = 3;
  // Frames per second over the last half second, for the panel.
  std::chrono::steady_clock::time_point fps_start = std::chrono::steady_clock::now();
  long fps_frames = 0;

  ImGuiContext* imgui = nullptr;

  // Several windows may exist (tests): each frame makes its own GL and ImGui contexts current.
  void activate() {
    if (window) glfwMakeContextCurrent(window);
    if (imgui) ImGui::SetCurrentContext(imgui);
  }

  ~LiveAppImpl() {
    activate();
    stop_recording();
    renderer.reset();  // needs the context
    if (imgui_gl) ImGui_ImplOpenGL3_Shutdown();
    if (imgui_glfw) ImGui_ImplGlfw_Shutdown();
    if (imgui) ImGui::DestroyContext(imgui);
    if (window) glfwDestroyWindow(window);
  }

  void say(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    messages.push_back(line);
    panel.last_output = line;
  }

  // Framebuffer pixels per window coordinate (1 except on HiDPI screens).
  double pixel_scale() const {
    int ww = 0, wh = 0, fw = 0, fh = 0;
    glfwGetWindowSize(window, &ww, &wh);
    glfwGetFramebufferSize(window, &fw, &fh);
    return ww > 0 ? double(fw) / ww : 1.0;
  }

  render::FrameLayout layout() const { return renderer->layout(panel.det_f_panel); }
  float panel_width() const { return panel.visible ? panel.width * panel.ui_scale : 0.0f; }

  // The part of the frame the world shows in and no panel covers (framebuffer px).
  render::PixelRect visible_rect() const {
    const render::FrameLayout L = layout();
    const double x0 = std::max(L.plot.x, panel_width() * pixel_scale());
    const double x1 = std::max(L.plot.x + L.plot.w, x0 + 50.0);  // overlaid: to the right edge
    return {x0, L.plot.y, x1 - x0, L.plot.h};
  }

  // Fits the view to the scene's stage, or with `bodies` to every node (F).
  void fit_view(bool bodies = false) {
    const render::PixelRect r = visible_rect();
    render::WorldBox b = render::scene_world_box(controller->settings());
    if (bodies) {
      const VecX& x = controller->simulation().x;
      b = {x[0], x[0], x[1], x[1]};
      for (Eigen::Index i = 0; i + 1 < x.size(); i += 2) {
        b = {std::min(b.x0, x[i]), std::max(b.x1, x[i]), std::min(b.y0, x[i + 1]),
             std::max(b.y1, x[i + 1])};
      }
      const double pad =
          0.15 * std::max({b.x1 - b.x0, b.y1 - b.y0, 0.1 * controller->settings().side});
      b = {b.x0 - pad, b.x1 + pad, b.y0 - pad, b.y1 + pad};
    }
    fit_bodies = bodies;
    view.fit({b.x0, b.y0, b.x1, b.y1}, r.x, r.y, r.w, r.h);
    fit_scene_index = controller->selected_scene();
    fit_n_seg = controller->settings().n_seg;
  }

  // The UI scale: ImGui's fonts rebuilt at the new size (sharp, not stretched), its
  // spacing scaled, and the det F panel at its 1280x720 design times the same scale.
  // Between frames only (fonts cannot change inside one).
  void apply_ui_scale() {
    const float scale = std::clamp(panel.ui_scale, kMinUiScale, kMaxUiScale);
    panel.ui_scale = scale;
    if (scale != applied_ui_scale) {
      applied_ui_scale = scale;
      build_fonts(scale);
      ImGui::GetStyle() = base_style;
      ImGui::GetStyle().ScaleAllSizes(scale);
      if (auto_fit) fit_view(fit_bodies);
    }
    const double frame_scale = std::min(renderer->width() / 1280.0, renderer->height() / 720.0);
    renderer->set_text_scale(scale * pixel_scale() / std::max(frame_scale, 1e-3));
  }

  void build_fonts(float scale);

  void resize_if_needed() {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    if (fw <= 0 || fh <= 0) return;  // minimised
    if (fw != renderer->width() || fh != renderer->height()) {
      if (const std::string e = renderer->resize(fw, fh); !e.empty()) say("invfree: live: " + e);
      const Vec2 keep = view.center;
      view.width = fw;
      view.height = fh;
      view.center = keep;
      if (auto_fit) fit_view(fit_bodies);
    }
  }

  void handle_action(Action a) {
    switch (a) {
      case Action::TogglePlay:
        controller->set_playing(!controller->playing());
        break;
      case Action::Step:
        controller->set_playing(false);
        controller->step_once();
        break;
      case Action::Reset:
        controller->reset();
        break;
      case Action::TogglePanel:
        panel.visible = !panel.visible;
        if (auto_fit) fit_view(fit_bodies);
        break;
      case Action::ToggleHelp:
        panel.show_help = !panel.show_help;
        break;
      case Action::Screenshot:
        screenshot_requested = true;
        break;
      case Action::ToggleRecord:
        toggle_recording();
        break;
      case Action::FitView:
        auto_fit = true;
        fit_view(true);
        break;
      case Action::UiScaleUp:
        panel.ui_scale = std::min(kMaxUiScale, panel.ui_scale + 0.25f);
        break;
      case Action::UiScaleDown:
        panel.ui_scale = std::max(kMinUiScale, panel.ui_scale - 0.25f);
        break;
      case Action::CycleDetFPanel:
        panel.det_f_panel =
            static_cast<render::PanelMode>((static_cast<int>(panel.det_f_panel) + 1) % 3);
        break;
      case Action::CycleColorRange:
        panel.color_range =
            static_cast<render::ColorRangeMode>((static_cast<int>(panel.color_range) + 1) % 3);
        break;
      case Action::Quit:
        glfwSetWindowShouldClose(window, GLFW_TRUE);
        break;
    }
  }
  bool screenshot_requested = false;
  std::vector<int> injected_keys;  // held by the last injection
  long recorded_revision = -1;     // the last state written to the recording

  void handle_keys() {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantCaptureKeyboard) return;  // typing into a panel field
    for (const auto& b : key_bindings()) {
      if (!ImGui::IsKeyPressed(b.key, false)) continue;
      if (auto a = action_for_key(b.key, io.KeyCtrl ? GLFW_MOD_CONTROL : 0); a && *a == b.action)
        handle_action(*a);
    }
  }

  // Mouse over the picture (not the panel): grab a node with the left button, pan with
  // the left button elsewhere or with the right/middle button, zoom with the wheel.
  void handle_mouse() {
    const ImGuiIO& io = ImGui::GetIO();
    const double ps = pixel_scale();
    const Vec2 mouse(io.MousePos.x * ps, io.MousePos.y * ps);
    const bool mouse_valid = ImGui::IsMousePosValid();
    if (drag != Drag::None) {
      const bool held = drag == Drag::Pull
                            ? io.MouseDown[0]
                            : (io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2]);
      if (!held || !mouse_valid) {
        if (drag == Drag::Pull) controller->end_pull();
        drag = Drag::None;
      } else if (drag == Drag::Pull) {
        // The target stays in the visible part of the picture: a body pulled toward a
        // panel stops at its edge instead of sliding behind it.
        const render::PixelRect r = visible_rect();
        const double m = 12.0 * ps;
        const Vec2 inside(std::clamp(mouse.x(), r.x + m, std::max(r.x + m, r.x + r.w - m)),
                          std::clamp(mouse.y(), r.y + m, std::max(r.y + m, r.y + r.h - m)));
        controller->move_pull(view.to_world(inside));
      } else {
        view.pan(mouse.x() - last_mouse.x(), mouse.y() - last_mouse.y());
        auto_fit = false;
      }
      last_mouse = mouse;
      return;
    }
    if (mouse_valid) {
      if (!pointer_seen) pointer_start = io.MousePos;
      pointer_seen = true;
      if (io.MousePos.x != pointer_start.x || io.MousePos.y != pointer_start.y)
        pointer_moved = true;
    }
    if (io.WantCaptureMouse || !mouse_valid) return;
    if (io.MouseWheel != 0.0f) {
      view.zoom_at(mouse, std::pow(1.15, io.MouseWheel));
      auto_fit = false;
    }
    if (io.MouseClicked[0]) {
      const int node = controller->nearest_node(view.to_world(mouse),
                                                kGrabRadiusPixels * ps / view.pixels_per_metre);
      if (node >= 0) {
        controller->begin_pull(node, view.to_world(mouse));
        drag = Drag::Pull;
      } else {
        drag = Drag::Pan;
      }
    } else if (io.MouseClicked[1] || io.MouseClicked[2]) {
      drag = Drag::Pan;
    }
    last_mouse = mouse;
  }

  // The grab spring and the node under the cursor, drawn over the picture.
  void draw_grab_markers() {
    const ImGuiIO& io = ImGui::GetIO();
    const double ps = pixel_scale();
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const Simulation& sim = controller->simulation();
    auto screen = [&](const Vec2& w) {
      const Vec2 s = view.to_screen(w) / ps;
      return ImVec2(static_cast<float>(s.x()), static_cast<float>(s.y()));
    };
    if (controller->pulling()) {
      const ImVec2 a = screen(sim.x.segment<2>(2 * controller->pull_node()));
      const ImVec2 b = screen(controller->pull_target());
      dl->AddLine(a, b, IM_COL32(20, 20, 20, 230), 2.5f);
      dl->AddCircleFilled(a, 5.0f, IM_COL32(250, 170, 0, 255));
      dl->AddCircle(b, 6.0f, IM_COL32(20, 20, 20, 230), 0, 2.0f);
      return;
    }
    if (drag != Drag::None || io.WantCaptureMouse || !ImGui::IsMousePosValid() || !pointer_moved)
      return;
    const Vec2 mouse(io.MousePos.x * ps, io.MousePos.y * ps);
    const int node = controller->nearest_node(view.to_world(mouse),
                                              kGrabRadiusPixels * ps / view.pixels_per_metre);
    if (node >= 0)
      dl->AddCircle(screen(sim.x.segment<2>(2 * node)), 7.0f, IM_COL32(250, 170, 0, 255), 0, 2.5f);
  }

  void toggle_recording() {
    if (recorder) {
      stop_recording();
      return;
    }
    std::string dir = options.record_dir;
    if (dir.empty() || std::filesystem::exists(dir)) {
      // A fresh numbered directory next to the screenshots.
      const std::filesystem::path base =
          options.screenshot_dir.empty() ? "." : options.screenshot_dir;
      for (int n = 1;; ++n) {
        char name[40];
        std::snprintf(name, sizeof name, "invfree_recording_%04d", n);
        if (!std::filesystem::exists(base / name)) {
          dir = (base / name).string();
          break;
        }
      }
    }
    options.record_dir.clear();  // --record names only the first recording
    start_recording(dir);
  }

  bool start_recording(const std::string& dir, bool force = false) {
    if (const OutputError e = record_output.open(dir, force)) {
      say("invfree: live: cannot record: " + e.message);
      return false;
    }
    recorder = std::make_unique<render::FrameWriter>(1, kPngCompression);
    record_dir = dir;
    record_frame = 0;
    panel.recording = true;
    say("recording to " + record_frame_path(dir, 0) + " ...");
    return true;
  }

  void stop_recording() {
    if (!recorder) return;
    const std::string e = recorder->finish();
    const long n = recorder->written();
    recorder.reset();
    record_output.close();
    panel.recording = false;
    if (!e.empty()) say("invfree: live: recording failed: " + e);
    say("recorded " + std::to_string(n) + " frame(s) to " + record_dir);
  }

  // The window's back buffer as drawn so far, RGBA8 bottom row first, opaque.
  std::vector<std::uint8_t> read_window_bottom_up() {
    const int w = renderer->width(), h = renderer->height();
    std::vector<std::uint8_t> rgba(static_cast<size_t>(w) * h * 4);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;  // the window is opaque
    return rgba;
  }
  Image read_window() {
    return image_from_bottom_up(read_window_bottom_up(), renderer->width(), renderer->height());
  }

  // This frame's simulation steps (none when paused); frame() waits for them before it
  // returns.
  std::future<void> start_steps() {
    if (!controller->playing()) return {};
#ifdef __EMSCRIPTEN__
    // The web page has no threads (-pthread would need cross-origin isolation headers from
    // the server): the steps run here, on the main thread, before the picture is drawn;
    // the n_seg slider's maximum keeps them within a frame (docs/web.md).
    controller->advance_frame();
    return {};
#else
    return std::async(std::launch::async, [this] { controller->advance_frame(); });
#endif
  }

  // A scripted frame's input (tests): the mouse, held keys and typed text, as if from GLFW.
  void inject_input(const Injection& inject) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(inject.x, inject.y);
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = inject.down[b];
    io.MouseWheel += inject.wheel;
    for (int k : injected_keys) io.KeysDown[k] = false;
    injected_keys.clear();
    for (int k : inject.keys) {
      if (k < 0 || k >= static_cast<int>(IM_ARRAYSIZE(io.KeysDown))) continue;
      io.KeysDown[k] = true;
      injected_keys.push_back(k);
    }
    io.KeyCtrl = inject.ctrl;
    for (char c : inject.text) io.AddInputCharacter(static_cast<unsigned char>(c));
  }

  // The ImGui frame: input, the panel and what it asks for, the help overlay, the banners
  // over the picture and the grab markers.
  void build_ui(const Injection* inject) {
    apply_ui_scale();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (inject) inject_input(*inject);
    ImGui::NewFrame();
    handle_keys();
    handle_mouse();

    const PanelRequests req = draw_panel(*controller, panel);
    if (req.screenshot) screenshot_requested = true;
    if (req.toggle_record) toggle_recording();
    if (req.fit_view) handle_action(Action::FitView);
    if (req.quit) handle_action(Action::Quit);
    // A new scene or mesh: show it whole (unless the user chose a view).
    if (controller->selected_scene() != fit_scene_index ||
        controller->settings().n_seg != fit_n_seg) {
      auto_fit = true;
      fit_view();
    }
    draw_help_overlay(panel);
    const render::PixelRect r = visible_rect();
    const double ps = pixel_scale();
    draw_banners(*controller, panel,
                 {static_cast<float>(r.x / ps), static_cast<float>(r.y / ps),
                  static_cast<float>((r.x + r.w) / ps), static_cast<float>((r.y + r.h) / ps)});
    draw_grab_markers();
    ImGui::Render();
  }

  // The picture: the shared renderer's frame with the live camera, drawn straight into the
  // window's back buffer under everything ImGui draws; a new state goes to the recording.
  // When playing, the next state is computed meanwhile (the GL work reads only the copied
  // state): on two cores the step and the renderer (llvmpipe's rasterizer threads too)
  // then overlap instead of queueing. Returns that computation, to be waited for.
  std::future<void> draw_picture() {
    const render::Camera cam{view.pixels_per_metre, view.to_screen(Vec2::Zero())};
    render::DrawOptions draw_options;
    draw_options.camera = cam;
    draw_options.framebuffer = 0;
    draw_options.edges = render::edges_legible(controller->settings(), view.pixels_per_metre);
    draw_options.panel = panel.det_f_panel != render::PanelMode::Hidden;
    draw_options.panel_overlay = panel.det_f_panel == render::PanelMode::Overlay;
    color_range.mode = panel.color_range;
    color_range.apply(controller->stats().min_det_f, controller->stats().max_det_f, &draw_options);
    const render::FrameState state =
        render::capture_frame_state(controller->simulation(), &controller->det_f());
    const long revision = controller->revision();
    // The next state is computed while this frame is drawn, rasterized and presented (the
    // GL work below reads only the copied state): on two cores the step and the renderer
    // (llvmpipe's rasterizer threads too) then overlap instead of queueing.
    std::future<void> stepping = start_steps();
    renderer->draw(state, draw_options);
    const int w = renderer->width(), h = renderer->height();
    // A recording holds each state once (from the initial one), not idle repeats.
    if (recorder && revision != recorded_revision) {
      recorded_revision = revision;
      if (!recorder->submit(record_frame_path(record_dir, record_frame), w, h,
                            read_window_bottom_up())) {
        stop_recording();
      } else {
        ++record_frame;
      }
    }
    return stepping;
  }

  // The screenshot asked for (Ctrl+P, the button), from `capture` when this frame has one.
  void save_screenshot(const Image* capture) {
    screenshot_requested = false;
    const std::string path = next_screenshot_path(options.screenshot_dir);
    if (const std::string e = write_png(path, capture ? *capture : read_window()); !e.empty())
      say("invfree: live: screenshot failed: " + e);
    else
      say("screenshot: " + path);
  }

  // Frames per second over the last half second, in the window title.
  void count_frame() {
    ++frames;
    ++fps_frames;
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - fps_start).count();
    if (dt >= 0.5) {
      char title[96];
      std::snprintf(title, sizeof title, "invfree live: %s, %.0f frames/s",
                    controller->settings().name.c_str(), fps_frames / dt);
      glfwSetWindowTitle(window, title);
      fps_frames = 0;
      fps_start = now;
    }
  }

  // Nothing will change until input arrives: paused, no drag, no recording, no scripted
  // frame count, no input in the last few frames (ImGui settles hover and focus in those).
  bool idle() const {
    return options.frames <= 0 && !controller->playing() && drag == Drag::None && !recorder &&
           !screenshot_requested && busy_frames <= 0;
  }

  void frame(const Injection* inject, Image* capture) {
    activate();
#ifndef __EMSCRIPTEN__  // (the browser calls each frame itself: nothing to wait for)
    constexpr bool can_wait = true;
#else
    constexpr bool can_wait = false;
#endif
    if (can_wait && !inject && idle()) {
      glfwWaitEventsTimeout(kIdleWaitSeconds);
      if (!g_input_seen && !glfwWindowShouldClose(window)) return;  // nothing new to draw
    } else {
      glfwPollEvents();
    }
    busy_frames = g_input_seen ? 3 : busy_frames - 1;
    g_input_seen = false;
    if (inject) busy_frames = 3;
    resize_if_needed();
    build_ui(inject);
    std::future<void> stepping = draw_picture();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, renderer->width(), renderer->height());
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (capture) *capture = read_window();
    if (screenshot_requested) save_screenshot(capture);
    glfwSwapBuffers(window);
    if (stepping.valid()) stepping.get();  // the controller is whole again when frame() returns
    count_frame();
  }
};

// ImGui's fonts at `scale`: the embedded DejaVu Sans (Latin, Greek for mu, lambda, nu, a
// few symbols) at 16 px and the banners' 40 px, times the scale; the GL texture is
// rebuilt when the backend is running.
void LiveAppImpl::build_fonts(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  static ImVector<ImWchar> ranges;
  if (ranges.empty()) {
    ImFontGlyphRangesBuilder builder;
    builder.AddRanges(io.Fonts->GetGlyphRangesDefault());
    builder.AddText("μλνσψΨΔ≤≥·×−²");
    builder.BuildRanges(&ranges);
  }
  io.Fonts->Clear();
  ImFontConfig cfg;
  cfg.FontDataOwnedByAtlas = false;  // the bytes live in the executable
  void* font_data = const_cast<unsigned char*>(invfree_chart_font_begin);
  const int font_bytes = static_cast<int>(invfree_chart_font_end - invfree_chart_font_begin);
  io.Fonts->AddFontFromMemoryTTF(font_data, font_bytes, std::round(kFontSize * scale), &cfg,
                                 ranges.Data);
  panel.big_font = io.Fonts->AddFontFromMemoryTTF(
      font_data, font_bytes, std::round(kBigFontSize * scale), &cfg, ranges.Data);
  if (imgui_gl && frames > 0) {  // (the first frame's NewFrame uploads it)
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
  }
}

LiveApp::LiveApp() : impl_(std::make_unique<LiveAppImpl>()) {}
LiveApp::~LiveApp() = default;

// The window with a current OpenGL 3.3 core context, and GL loaded from it. Returns "" or
// why not (for no_window_message).
static std::string open_window(LiveAppImpl& a, const LiveOptions& options) {
  glfwSetErrorCallback(on_glfw_error);
  g_glfw_error.clear();
  if (!g_glfw_initialized && !glfwInit())
    return g_glfw_error.empty() ? "GLFW could not start" : g_glfw_error;
  g_glfw_initialized = true;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  a.window = glfwCreateWindow(options.width, options.height, "invfree live", nullptr, nullptr);
  if (!a.window)
    return "no OpenGL 3.3 window: " +
           (g_glfw_error.empty() ? std::string("unknown") : g_glfw_error);
  glfwMakeContextCurrent(a.window);
  glfwSwapInterval(options.vsync ? 1 : 0);
  const auto get_proc = reinterpret_cast<render::GlGetProcAddress>(glfwGetProcAddress);
  return render::load_gl_api(get_proc, &a.gl);
}

// The shared renderer at the window's framebuffer size. Multisampling only on real GPUs:
// Mesa's software rasterizers (llvmpipe under Xvfb) shade every sample, so 4x would
// multiply the cost of filling the frame. Returns "" or why not.
static std::string create_renderer(LiveAppImpl& a) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(a.window, &fw, &fh);
  const char* gl_renderer = reinterpret_cast<const char*>(a.gl.GetString(GL_RENDERER));
  const std::string renderer_name = gl_renderer ? gl_renderer : "";
  const bool software = renderer_name.find("llvmpipe") != std::string::npos ||
                        renderer_name.find("softpipe") != std::string::npos ||
                        renderer_name.find("swrast") != std::string::npos;
  const auto get_proc = reinterpret_cast<render::GlGetProcAddress>(glfwGetProcAddress);
  std::string e;
  const int samples = a.options.samples > 0 ? a.options.samples : (software ? 1 : 4);
  a.renderer = render::Renderer::create(get_proc, std::max(fw, 1), std::max(fh, 1), &e, samples);
  return a.renderer ? "" : "the renderer could not start: " + e;
}

// Dear ImGui on the window: its context (writing no files), style, the fonts (the
// embedded DejaVu Sans) and the GLFW and OpenGL3 backends. Returns "" or why not.
static std::string start_imgui(LiveAppImpl& a) {
  IMGUI_CHECKVERSION();
  a.imgui = ImGui::CreateContext();
  ImGui::SetCurrentContext(a.imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written next to the user's files
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().FrameRounding = 3.0f;
  a.base_style = ImGui::GetStyle();
  // (The fonts: build_fonts, at the UI scale, before the first frame.)
  // Ours first: ImGui's backend installs its own and calls these from them.
  glfwSetKeyCallback(a.window, on_key);
  glfwSetCharCallback(a.window, on_char);
  glfwSetCursorPosCallback(a.window, on_cursor);
  glfwSetMouseButtonCallback(a.window, on_button);
  glfwSetScrollCallback(a.window, on_scroll);
  glfwSetFramebufferSizeCallback(a.window, on_size);
  glfwSetWindowFocusCallback(a.window, on_focus);
  glfwSetCursorEnterCallback(a.window, on_enter);
  glfwSetWindowRefreshCallback(a.window, on_refresh);
  if (!ImGui_ImplGlfw_InitForOpenGL(a.window, true)) return "ImGui's GLFW backend could not start";
  a.imgui_glfw = true;
  if (!ImGui_ImplOpenGL3_Init(a.gl.opengl_es ? "#version 300 es" : "#version 330 core"))
    return "ImGui's OpenGL3 backend could not start";
  a.imgui_gl = true;
  return "";
}

// The UI scale a window starts with: its content scale (HiDPI) times how much larger than
// 1280x720 it is (never smaller), in steps of 0.25: 1 at 1280x720, 1.5 at 1920x1080.
static float default_ui_scale(GLFWwindow* window) {
  float cx = 1.0f;
#ifndef __EMSCRIPTEN__
  float cy = 1.0f;
  glfwGetWindowContentScale(window, &cx, &cy);
#endif
  int w = 0, h = 0;
  glfwGetWindowSize(window, &w, &h);
  const float size = std::max(1.0f, std::min(w / 1280.0f, h / 720.0f));
  const float s = std::round(std::max(cx, 0.5f) * size * 4.0f) / 4.0f;
  return std::clamp(s, kMinUiScale, kMaxUiScale);
}

std::unique_ptr<LiveApp> LiveApp::create(const LiveOptions& options, std::string* error) {
  if (!display_available()) {
    *error = no_window_message("no display: DISPLAY is not set");
    return nullptr;
  }
  std::unique_ptr<LiveApp> app(new LiveApp());
  LiveAppImpl& a = *app->impl_;
  a.options = options;
  std::string e = open_window(a, options);
  if (e.empty()) e = create_renderer(a);
  if (e.empty()) e = start_imgui(a);
  if (!e.empty()) {
    *error = no_window_message(e);
    return nullptr;
  }
  a.controller = std::make_unique<LiveController>(options.scenes, options.selected);
  a.controller->set_playing(!options.paused);
  a.controller->steps_per_frame = options.steps_per_frame;
  a.panel.visible = !options.hide_panel;
  a.panel.det_f_panel = options.det_f_panel;
  a.panel.color_range = options.color_range;
  a.panel.ui_scale = options.ui_scale > 0.0f ? options.ui_scale : default_ui_scale(a.window);
  a.apply_ui_scale();
  a.panel.max_segments = options.max_segments;
  a.view.width = a.renderer->width();
  a.view.height = a.renderer->height();
  a.fit_view();
  if (!options.record_dir.empty()) {
    const std::string dir = options.record_dir;
    a.options.record_dir.clear();
    if (!a.start_recording(dir, options.record_force)) {
      *error = "cannot record to " + dir + " (see above)";
      return nullptr;
    }
  }
  return app;
}

void LiveApp::frame(const Injection* inject, Image* capture) {
  impl_->frame(inject, capture);
}
bool LiveApp::should_close() const {
  return glfwWindowShouldClose(impl_->window);
}
long LiveApp::frames_drawn() const {
  return impl_->frames;
}
LiveController& LiveApp::controller() {
  return *impl_->controller;
}
Vec2 LiveApp::to_window(const Vec2& world) const {
  return impl_->view.to_screen(world) / impl_->pixel_scale();
}
const std::map<std::string, WidgetRect>& LiveApp::widget_rects() const {
  return impl_->panel.rects;
}
const std::vector<std::string>& LiveApp::messages() const {
  return impl_->messages;
}
LiveApp::View LiveApp::view() const {
  return {impl_->panel.ui_scale, impl_->panel.det_f_panel, impl_->panel.color_range};
}

int run_live(const LiveOptions& options) {
  std::string error;
  auto app = LiveApp::create(options, &error);
  if (!app) {
    std::fprintf(stderr, "invfree: live: %s\n", error.c_str());
    return exit_code::kOutputFailed;
  }
  const auto start = std::chrono::steady_clock::now();
  const bool want_last = !options.screenshot_file.empty();
  Image last;
  for (long f = 0; !app->should_close() && (options.frames <= 0 || f < options.frames) &&
                   !(options.stop && options.stop());
       ++f) {
    const bool final_frame = options.frames > 0 && f + 1 == options.frames;
    app->frame(nullptr, want_last && final_frame ? &last : nullptr);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (want_last) {
    if (last.rgba.empty()) app->frame(nullptr, &last);  // closed early: this frame then
    if (const std::string e = write_png(options.screenshot_file, last); !e.empty()) {
      std::fprintf(stderr, "invfree: live: %s\n", e.c_str());
      return exit_code::kOutputFailed;
    }
    std::printf("screenshot: %s\n", options.screenshot_file.c_str());
  }
  const LiveController& lc = app->controller();
  if (options.bench) {
    const long frames = app->frames_drawn();
    const SceneDef& s = lc.settings();
    const long steps = lc.steps_total();
    std::printf(
        "live bench: %ld frames in %.2f s = %.1f frames/s (scene %s, n_seg %d, h %g, %d "
        "step(s)/frame; %ld steps, "
        "%.2f ms/step, %.2f ms/frame)\n",
        frames, seconds, frames / seconds, s.name.c_str(), s.n_seg, s.h, lc.steps_per_frame, steps,
        steps ? lc.step_ms_total() / steps : 0.0, 1e3 * seconds / std::max<long>(1, frames));
  }
  if (!lc.banner.empty()) {
    std::fprintf(stderr, "invfree: live: %s\n", lc.banner.c_str());
    if (options.frames > 0) return exit_code::kRunFailed;
  }
  return exit_code::kOk;
}

}  // namespace invfree::live
