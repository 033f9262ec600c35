// LiveApp: one frame of the live window put together from its parts: the window and ImGui
// (live_window.h), scripted input (input_injection.h), the keys' actions (key_bindings.h),
// the mouse (mouse_gestures.h), the view (auto_fit_view.h), the panel (live_panel.h), the
// inspected triangle and its windows (triangle_inspection.h, inspector_panel.h,
// landscape_window.h), the picture (app/render/renderer.h), the outputs
// (frame_recording.h, window_capture.h), and the simulation's steps, which run while the
// picture is drawn.
#include "app/live/live_app.h"

#include <GL/glcorearb.h>  // before GLFW's header, which would include GL/gl.h instead
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>  // ClosePopupToLevel: Esc closes an open picker

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <future>
#include <optional>

#include "app/live/auto_fit_view.h"
#include "app/live/frame_rate.h"
#include "app/live/failure_mark.h"
#include "app/live/frame_recording.h"
#include "app/live/input_injection.h"
#include "app/live/input_queue.h"
#include "app/live/inspector_panel.h"
#include "app/live/key_bindings.h"
#include "app/live/landscape_window.h"
#include "app/live/live_panel.h"
#include "app/live/panel_layout.h"
#include "app/live/live_window.h"
#include "app/live/method_choice.h"
#include "app/live/mouse_gestures.h"
#include "app/live/presentation.h"
#include "app/live/real_time_rate.h"
#include "app/live/window_capture.h"
#include "app/render/projector_mesh.h"
#include "app/render/renderer.h"
#include "triangle_fields.h"

namespace invfree::live {

namespace {

// Frames drawn after input arrives before the window may idle: ImGui settles hover and
// focus in those.
constexpr int kBusyFrames = 3;

// CPU time of the calling thread (ms): what a part of the frame costs, whatever else the
// machine runs meanwhile (the benchmark line's breakdown).
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

std::string no_window_message(const std::string& reason) {
  return "cannot open the live window (" + reason +
         "); for pictures without a display use `invfree render`, or run `xvfb-run -a invfree live "
         "...`";
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
  LiveWindow window;  // declared before what draws into it: destroyed after it
  std::unique_ptr<render::Renderer> renderer;
  std::unique_ptr<LiveController> controller;
  PanelState panel;
  AutoFitView view;
  InputInjection injection;
  MouseGestures mouse;
  TriangleInspection inspection;
  LandscapePanelCache landscape_cache;
  LiveApp::PartTimes part_times;
  long empty_clicks = 0;
  FrameRecording recording;
  bool screenshot_requested = false;
  std::vector<std::string> messages;
  long frames = 0;
  FrameRateMeter frame_rate;
  float applied_ui_scale = 0.0f;          // the UI scale the fonts were built at
  render::ColorRangeTracker color_range;  // the det F colour range over the run
  // What the field's range over the run was gathered for: a new colouring or mesh starts it
  // again (det F's range is kept, as before).
  TriangleField field_range_of = TriangleField::DetF;
  long field_range_generation = 0;
  int busy_frames = kBusyFrames;  // frames left to draw before idling
  long color_range_restarts = -1;  // the controller's restart the colour range's run began at
  RealTimeRate real_time;
  bool presenting = false;             // presentation mode (key P)
  bool panel_before_presenting = true;  // the panel's visibility to return to

  ~LiveAppImpl() {
    window.activate();
    stop_recording();
    renderer.reset();  // needs the context
  }

  void say(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    messages.push_back(line);
    panel.last_output = line;
  }
  FrameRecording::Say sayer() {
    return [this](const std::string& line) { say(line); };
  }

  // The part of the frame the world shows in and no panel covers (framebuffer px).
  render::PixelRect visible_rect() const {
    const render::FrameLayout L = renderer->layout(panel.det_f_panel);
    const double ps = window.pixel_scale();
    const float panel_width = place_panel(float(renderer->width() / ps),
                                          float(renderer->height() / ps), panel.ui_scale,
                                          panel.visible)
                                  .reserved;
    const double x0 = std::max(L.plot.x, panel_width * ps);
    const double x1 = std::max(L.plot.x + L.plot.w, x0 + 50.0);  // overlaid: to the right edge
    return {x0, L.plot.y, x1 - x0, L.plot.h};
  }

  // Where the view frames the world: the visible part less the det F panel laid over the
  // picture (the world goes on under it, translucent, but the body is framed beside it).
  render::PixelRect framing_rect() const {
    render::PixelRect r = visible_rect();
    const render::FrameLayout L = renderer->layout(panel.det_f_panel);
    if (L.overlay && L.panel.x > r.x + 50.0) r.w = std::min(r.w, L.panel.x - r.x);
    return r;
  }

  // The UI scale, clamped: ImGui's fonts and spacing, and the det F panel at its 1280x720
  // design times the same scale. Between frames only (fonts cannot change inside one).
  void apply_ui_scale() {
    const float scale = std::clamp(panel.ui_scale, kMinUiScale, kMaxUiScale);
    panel.ui_scale = scale;
    if (scale != applied_ui_scale) {
      applied_ui_scale = scale;
      panel.big_font = window.set_ui_scale(scale);
      view.refit(*controller, framing_rect());
    }
    const double frame_scale = std::min(renderer->width() / 1280.0, renderer->height() / 720.0);
    renderer->set_text_scale(scale * window.pixel_scale() / std::max(frame_scale, 1e-3));
  }

  void resize_if_needed() {
    int fw = 0, fh = 0;
    window.framebuffer_size(&fw, &fh);
    if (fw <= 0 || fh <= 0) return;  // minimised
    if (fw != renderer->width() || fh != renderer->height()) {
      if (const std::string e = renderer->resize(fw, fh); !e.empty()) say("invfree: live: " + e);
      view.set_size(fw, fh);
      view.refit(*controller, framing_rect());
    }
  }

  void handle_action(Action a);
  void handle_keys();
  void back();
  void set_presenting(bool on);
  void pick(const Vec2& world);
  void select(int t) {
    inspection.select(controller->simulation(), t, controller->mesh_generation());
    panel.place_inspector = true;
  }
  void draw_inspection_windows(const WidgetRect& area);

  bool start_recording(const std::string& dir, bool force = false) {
    const bool started = recording.start(dir, force, sayer());
    panel.recording = recording.active();
    return started;
  }
  void stop_recording() {
    recording.stop(sayer());
    panel.recording = recording.active();
  }
  void toggle_recording() {
    if (recording.active()) {
      stop_recording();
      return;
    }
    const std::string dir = new_recording_dir(options.record_dir, options.screenshot_dir);
    options.record_dir.clear();  // --record names only the first recording
    start_recording(dir);
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

  void build_ui(const Injection* inject, const InputFrame* input, bool render);
  std::future<void> draw_picture();

  // The screenshot asked for (Ctrl+P, the button), from `capture` when this frame has one.
  void save_requested_screenshot(const Image* capture) {
    screenshot_requested = false;
    say(save_screenshot(
        options.screenshot_dir,
        capture ? *capture : read_window(window.gl(), renderer->width(), renderer->height())));
  }

  // Frames per second in the window title.
  void count_frame() {
    ++frames;
    real_time.count(controller->simulation().time, controller->playing());
    if (const std::optional<double> rate = frame_rate.count()) {
      char title[96];
      const std::optional<double> sim_rate = real_time.rate();
      std::snprintf(title, sizeof title, "invfree live: %s, %.0f frames/s%s%s",
                    controller->settings().name.c_str(), *rate, sim_rate ? ", " : "",
                    sim_rate ? RealTimeRate::text(*sim_rate).c_str() : "");
      window.set_title(title);
    }
  }

  // Nothing will change until input arrives: paused, no drag, no recording, no scripted
  // frame count, no input in the last few frames.
  bool idle() const {
    return options.frames <= 0 && !controller->playing() && !mouse.dragging() &&
           !recording.active() && !screenshot_requested && busy_frames <= 0;
  }

  void frame(const Injection* inject, Image* capture);
};

void LiveAppImpl::handle_action(Action a) {
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
      view.refit(*controller, framing_rect());
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
      view.fit_bodies(*controller, framing_rect());
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
    case Action::Presentation:
      set_presenting(!presenting);
      break;
    case Action::Back:
      back();
      break;
    case Action::Quit:
      window.request_close();
      break;
  }
}

// Esc closes what is open, the innermost first, and never quits: a stray Esc (the picker
// was open, the help shown) used to end the run and lose every edited setting.
void LiveAppImpl::back() {
  if (ImGui::GetCurrentContext()->OpenPopupStack.Size > 0)
    ImGui::ClosePopupToLevel(0, true);  // a picker's list
  else if (panel.show_help)
    panel.show_help = false;
  else if (presenting)
    set_presenting(false);
  else if (inspection.selected() >= 0)
    inspection.release();
  else
    controller->note = "Esc closes pickers and overlays; Ctrl+Q quits";
}

// Presentation mode: full screen without the panel; leaving it restores both.
void LiveAppImpl::set_presenting(bool on) {
  if (on == presenting) return;
  presenting = on;
  if (on) panel_before_presenting = panel.visible;
  panel.visible = on ? false : panel_before_presenting;
  window.set_fullscreen(on);
  resize_if_needed();
  view.refit(*controller, framing_rect());
}

void LiveAppImpl::handle_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;  // typing into a panel field (its Esc cancels the typing)
  if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) back();  // also while a picker is open
  if (io.WantCaptureKeyboard) return;
  for (const auto& b : key_bindings()) {
    if (b.key == kTypedKey || b.action == Action::Back || !ImGui::IsKeyPressed(b.key, false))
      continue;
    if (auto a = action_for_key(b.key, io.KeyCtrl ? GLFW_MOD_CONTROL : 0); a && *a == b.action)
      handle_action(*a);
  }
  for (ImWchar c : io.InputQueueCharacters)  // + and -, whichever key typed them
    if (const std::optional<Action> a = action_for_char(c)) handle_action(*a);
}

// A click on the picture: the triangle under it is inspected; a click on empty space lets
// go of the one inspected, or (none was) is counted for the web page's tap.
void LiveAppImpl::pick(const Vec2& world) {
  const Simulation& sim = controller->simulation();
  if (const std::optional<int> t = triangle_at(sim, world))
    select(*t);
  else if (inspection.selected() >= 0)
    inspection.release();
  else
    ++empty_clicks;
}

// The inspector's window (closing it, its x, lets go of the triangle) and the energy
// landscape's window. The inspector goes over the det F panel beside the picture when there
// is one and the landscape's window does not hold its lower part: that panel's scene, model,
// mu and lambda the inspector repeats, and the body stays in view. Otherwise it goes over
// the picture, on the side away from its triangle.
void LiveAppImpl::draw_inspection_windows(const WidgetRect& area) {
  const Simulation& sim = controller->simulation();
  inspection.update(sim, controller->mesh_generation());
  if (const Inspected* in = inspection.inspected()) {
    WidgetRect where = area;
    bool inspector_left = false;
    const bool over_panel = panel.det_f_panel == render::PanelMode::Side && !panel.show_landscape;
    if (over_panel) {
      const ImGuiViewport* vp = ImGui::GetMainViewport();
      where.x0 = area.x1;
      where.x1 = vp->WorkPos.x + vp->WorkSize.x;
    } else {
      Vec2 c = Vec2::Zero();
      for (int node : sim.mesh.triangles[static_cast<size_t>(in->triangle)])
        c += sim.x.segment<2>(2 * node);
      const Vec2 p = view.transform().to_screen(c / 3.0) / window.pixel_scale();
      inspector_left = p.x() > 0.5 * (area.x0 + area.x1);
    }
    if (!draw_inspector(*in, panel, where, inspector_left, !over_panel)) inspection.release();
  }
  draw_landscape_window(sim, inspection.selected(), panel, landscape_cache);
}

// The ImGui frame: input, the panel and what it asks for, the inspector, the help overlay,
// the banners over the picture and the grab markers.
// `input`: the frame's share of the window's events (input_queue.h); with `render` false the
// frame only takes input (an earlier share of this frame's events): it ends without drawing.
void LiveAppImpl::build_ui(const Injection* inject, const InputFrame* input, bool render) {
  apply_ui_scale();
  window.begin_imgui_frame(inject ? nullptr : input);
  if (inject) injection.apply(*inject);
  ImGui::NewFrame();
  handle_keys();
  const double ps = window.pixel_scale();
  if (const std::optional<Vec2> click = mouse.handle(*controller, view, visible_rect(), ps))
    pick(*click);

  const PanelRequests req = draw_panel(*controller, panel);
  if (req.screenshot) screenshot_requested = true;
  if (req.toggle_record) toggle_recording();
  if (req.fit_view) handle_action(Action::FitView);
  if (req.toggle_panel) handle_action(Action::TogglePanel);
  if (req.quit) window.request_close();  // (Esc, Action::Quit, first releases a triangle)
  // A new scene or mesh: its default view (even after the user chose a view); the follow
  // camera's next step.
  view.update(*controller, framing_rect());
  const render::PixelRect r = visible_rect();
  const WidgetRect area{static_cast<float>(r.x / ps), static_cast<float>(r.y / ps),
                        static_cast<float>((r.x + r.w) / ps), static_cast<float>((r.y + r.h) / ps)};
  const double inspection_start = thread_cpu_ms();
  if (panel.touch) panel.rects["picture"] = area;  // where the world shows (the page's tests)
  draw_inspection_windows(area);
  part_times.inspection_ms += thread_cpu_ms() - inspection_start;
  draw_help_overlay(panel);
  draw_banners(*controller, panel, area);
  if (!controller->banner.empty()) draw_failure_mark(*controller, area);
  if (presenting)
    draw_presentation_readouts(*controller, panel, area, real_time.rate(),
                               solver_caption(controller->settings()));
  else if (options.frames <= 0 && controller->playing() && real_time.rate())
    draw_real_time_rate(*real_time.rate(), area);  // (a scripted run's picture: no clock)
  mouse.draw_markers(*controller, view.transform(), ps);
  if (render)
    ImGui::Render();
  else
    ImGui::EndFrame();
}

// The picture: the shared renderer's frame with the live camera, drawn straight into the
// window's back buffer under everything ImGui draws; a new state goes to the recording.
// When playing, the next state is computed meanwhile (the GL work reads only the copied
// state): on two cores the step and the renderer (llvmpipe's rasterizer threads too)
// then overlap instead of queueing. Returns that computation, to be waited for.
std::future<void> LiveAppImpl::draw_picture() {
  const ViewTransform& v = view.transform();
  render::DrawOptions draw_options;
  draw_options.camera = render::Camera{v.pixels_per_metre, v.to_screen(Vec2::Zero())};
  draw_options.framebuffer = 0;
  draw_options.edges = render::edges_legible(controller->settings(), v.pixels_per_metre);
  draw_options.panel = panel.det_f_panel != render::PanelMode::Hidden;
  draw_options.panel_overlay = panel.det_f_panel == render::PanelMode::Overlay;
  draw_options.selected_triangle = inspection.selected();
  draw_options.stress_glyphs = panel.stress_glyphs;
  color_range.mode = panel.color_range;
  if (controller->restarts() != color_range_restarts) {  // a reset or another scene
    color_range.reset();
    color_range_restarts = controller->restarts();
  }
  // The automatic ranges from the bulk of det F (its 10th to 90th percentile), as render's:
  // a scale to the extremes paints the squeezed bulk the pale tint of the fixed scale.
  const auto [det_lo, det_hi] = controller->det_f().empty()
                                    ? std::pair(controller->stats().min_det_f,
                                                controller->stats().max_det_f)
                                    : render::bulk_det_f_range(controller->det_f());
  color_range.apply(det_lo, det_hi, &draw_options);
  const double capture_start = thread_cpu_ms();
  const render::FrameState state = render::capture_frame_state(
      controller->simulation(), &controller->det_f(), {panel.color_by, panel.stress_glyphs});
  part_times.capture_ms += thread_cpu_ms() - capture_start;
  if (panel.color_by != field_range_of || controller->mesh_generation() != field_range_generation) {
    color_range.field_seen = false;
    field_range_of = panel.color_by;
    field_range_generation = controller->mesh_generation();
  }
  color_range.apply_field(state, &draw_options);
  const long revision = controller->revision();
  std::future<void> stepping = start_steps();
  renderer->draw(state, draw_options);
  // A recording holds each state once (from the initial one), not idle repeats.
  if (!recording.add(revision, window.gl(), renderer->width(), renderer->height()))
    stop_recording();
  return stepping;
}

void LiveAppImpl::frame(const Injection* inject, Image* capture) {
  window.activate();
#ifndef __EMSCRIPTEN__  // (the browser calls each frame itself: nothing to wait for)
  constexpr bool can_wait = true;
#else
  constexpr bool can_wait = false;
#endif
  const bool wait = can_wait && !inject && idle();
  const bool input = window.take_events(wait);
  if (wait && !input && !window.should_close()) return;  // nothing new to draw
  busy_frames = input || inject ? kBusyFrames : busy_frames - 1;
  resize_if_needed();
  // Every event in order: the earlier shares of this frame's input each get an ImGui frame
  // of their own (no drawing), so a press and its release between two slow frames both act.
  std::vector<InputFrame> events = window.take_input();
  if (!inject)
    for (std::size_t k = 0; k + 1 < events.size(); ++k) build_ui(nullptr, &events[k], false);
  build_ui(inject, inject ? nullptr : &events.back(), true);
  std::future<void> stepping = draw_picture();
  window.draw_imgui(renderer->width(), renderer->height());
  if (capture) *capture = read_window(window.gl(), renderer->width(), renderer->height());
  if (screenshot_requested) save_requested_screenshot(capture);
  window.present();
  if (stepping.valid()) stepping.get();  // the controller is whole again when frame() returns
  count_frame();
}

LiveApp::LiveApp() : impl_(std::make_unique<LiveAppImpl>()) {}
LiveApp::~LiveApp() = default;

std::unique_ptr<LiveApp> LiveApp::create(const LiveOptions& options, std::string* error) {
  if (!display_available()) {
    *error = no_window_message("no display: DISPLAY is not set");
    return nullptr;
  }
  std::unique_ptr<LiveApp> app(new LiveApp());
  LiveAppImpl& a = *app->impl_;
  a.options = options;
  std::string e = a.window.open(options.width, options.height, options.vsync);
  if (e.empty()) {
    a.renderer = a.window.create_renderer(options.samples, &e);
    if (!a.renderer) e = "the renderer could not start: " + e;
  }
  if (e.empty()) e = a.window.start_imgui();
  if (!e.empty()) {
    *error = no_window_message(e);
    return nullptr;
  }
  std::vector<SceneChoice> scenes = options.scenes;
  for (size_t i = 0; i < scenes.size(); ++i)
    if (!(options.keep_selected_mesh && static_cast<int>(i) == options.selected))
      render::refine_for_projector(scenes[i].scene, options.min_n_seg);
  a.controller = std::make_unique<LiveController>(std::move(scenes), options.selected);
  a.controller->set_playing(!options.paused);
  a.controller->steps_per_frame = options.steps_per_frame;
  a.panel.visible = !options.hide_panel;
  a.panel.det_f_panel = options.det_f_panel;
  a.panel.color_range = options.color_range;
  a.panel.color_by = options.color_by;
  a.panel.stress_glyphs = options.stress_glyphs;
  a.panel.show_landscape = options.show_landscape;
  if (options.select_triangle >= 0) a.select(options.select_triangle);
  a.panel.ui_scale = options.ui_scale > 0.0f ? options.ui_scale : a.window.default_ui_scale();
  a.apply_ui_scale();
  a.panel.touch = options.touch_controls;
  if (options.touch_controls && !options.hide_panel) {
    const double ps = a.window.pixel_scale();
    const float det_f_w = float(a.renderer->layout(a.panel.det_f_panel).panel.w / ps);
    a.panel.visible = panel_starts_open(float(a.renderer->width() / ps),
                                        float(a.renderer->height() / ps), a.panel.ui_scale,
                                        a.panel.det_f_panel == render::PanelMode::Side ? det_f_w : 0.0f);
  }
  a.panel.max_segments = options.max_segments;
  a.view.set_size(a.renderer->width(), a.renderer->height());
  a.view.set_follow(options.follow_camera);
  a.view.fit(*a.controller, a.framing_rect());
  if (options.presentation) a.set_presenting(true);
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
  return impl_->window.should_close();
}
long LiveApp::frames_drawn() const {
  return impl_->frames;
}
LiveController& LiveApp::controller() {
  return *impl_->controller;
}
Vec2 LiveApp::to_window(const Vec2& world) const {
  return impl_->view.transform().to_screen(world) / impl_->window.pixel_scale();
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
const Inspected* LiveApp::inspected() const {
  return impl_->inspection.inspected();
}
void LiveApp::select_triangle(int t) {
  LiveAppImpl& a = *impl_;
  if (t >= 0 && t < a.controller->simulation().mesh.triangle_count())
    a.select(t);
  else
    a.inspection.release();
}
LiveApp::PartTimes LiveApp::part_times() const {
  return impl_->part_times;
}
long LiveApp::empty_clicks() const {
  return impl_->empty_clicks;
}
TriangleField LiveApp::color_by() const {
  return impl_->panel.color_by;
}
void LiveApp::set_color_by(TriangleField field) {
  impl_->panel.color_by = field;
}
bool LiveApp::presenting() const {
  return impl_->presenting;
}
std::optional<double> LiveApp::real_time_rate() const {
  return impl_->real_time.rate();
}
std::pair<double, double> LiveApp::color_range_run() const {
  return {impl_->color_range.run_lo, impl_->color_range.run_hi};
}

}  // namespace invfree::live
