#include "app/live/live_window.h"

#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>

#include "app/live/live_app.h"
#include "app/render/renderer.h"

// The DejaVu Sans file embedded by app/plot/font.cpp (the chart font): ImGui's text uses
// the same face as the rendered frames, with no run-time font lookup.
extern "C" const unsigned char invfree_chart_font_begin[];
extern "C" const unsigned char invfree_chart_font_end[];

namespace invfree::live {

namespace {

constexpr float kFontSize = 16.0f, kBigFontSize = 40.0f;  // at UI scale 1
// While nothing changes the window waits for input this long at most (so that Ctrl-C and
// --frames still end it): no frame is drawn meanwhile.
constexpr double kIdleWaitSeconds = 0.25;

// GLFW's description of the last error on this thread ("" when none), which it then
// forgets: the one-line messages name it.
std::string take_glfw_error() {
#ifdef __EMSCRIPTEN__
  return "";  // the browser's GLFW records no errors
#else
  const char* description = nullptr;
  if (glfwGetError(&description) == GLFW_NO_ERROR) return "";
  return description ? description : "unknown error";
#endif
}

}  // namespace

void LiveWindow::note_input(GLFWwindow* window) {
  if (auto* self = static_cast<LiveWindow*>(glfwGetWindowUserPointer(window)))
    self->input_seen_ = true;
}

void LiveWindow::queue_input(GLFWwindow* window, const InputEvent& e) {
  if (auto* self = static_cast<LiveWindow*>(glfwGetWindowUserPointer(window))) {
    self->queue_.push(e);
    self->input_seen_ = true;
  }
}

LiveWindow::~LiveWindow() {
  activate();
  if (imgui_gl_) ImGui_ImplOpenGL3_Shutdown();
  if (imgui_glfw_) ImGui_ImplGlfw_Shutdown();
  if (imgui_) ImGui::DestroyContext(imgui_);
  if (window_) {
    glfwSetWindowUserPointer(window_, nullptr);  // its last events find no window
    glfwDestroyWindow(window_);
  }
}

// GLFW is initialised by the first window and left so until the process exits (a second
// glfwInit returns at once). glfwTerminate would unload libGL and Mesa's driver, and the
// allocations they still hold would become unreachable (LeakSanitizer reports them under
// the sanitize preset); the system reclaims all of it at exit anyway.
std::string LiveWindow::open(int width, int height, bool vsync) {
  take_glfw_error();  // an earlier window's
  if (!glfwInit()) {
    const std::string e = take_glfw_error();
    return e.empty() ? "GLFW could not start" : e;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, "invfree live", nullptr, nullptr);
  if (!window_) {
    const std::string e = take_glfw_error();
    return "no OpenGL 3.3 window: " + (e.empty() ? std::string("unknown") : e);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(vsync ? 1 : 0);
  const auto get_proc = reinterpret_cast<render::GlGetProcAddress>(glfwGetProcAddress);
  return render::load_gl_api(get_proc, &gl_);
}

std::string LiveWindow::start_imgui() {
  IMGUI_CHECKVERSION();
  imgui_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written next to the user's files
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().FrameRounding = 3.0f;
  base_style_ = ImGui::GetStyle();
  // Any input ends the idle wait, and every key, character, button, move and wheel event
  // goes into the queue in order (input_queue.h) instead of straight into ImGui's io, where
  // the backend's callbacks would keep only each frame's last state.
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_REPEAT) queue_input(w, {InputEvent::Key, key, action == GLFW_PRESS});
    note_input(w);
  });
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned c) {
    queue_input(w, {InputEvent::Char, static_cast<int>(c)});
  });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    queue_input(w, {InputEvent::Move, 0, false, static_cast<float>(x), static_cast<float>(y)});
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
#ifdef __EMSCRIPTEN__
    // The browser's GLFW reports a touch's press without a move to where it is.
    double x = 0, y = 0;
    glfwGetCursorPos(w, &x, &y);
    queue_input(w, {InputEvent::Move, 0, false, static_cast<float>(x), static_cast<float>(y)});
#endif
    queue_input(w, {InputEvent::Button, button, action == GLFW_PRESS});
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double x, double y) {
    queue_input(w, {InputEvent::Scroll, 0, false, static_cast<float>(x), static_cast<float>(y)});
  });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { note_input(w); });
  glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int focused) {
    ImGui_ImplGlfw_WindowFocusCallback(w, focused);
    note_input(w);
  });
  glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int entered) {
    ImGui_ImplGlfw_CursorEnterCallback(w, entered);
    if (!entered) queue_input(w, {InputEvent::Leave});
    note_input(w);
  });
  // The window was uncovered: draw it again.
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { note_input(w); });
  if (!ImGui_ImplGlfw_InitForOpenGL(window_, false)) return "ImGui's GLFW backend could not start";
  imgui_glfw_ = true;
  if (!ImGui_ImplOpenGL3_Init(gl_.opengl_es ? "#version 300 es" : "#version 330 core"))
    return "ImGui's OpenGL3 backend could not start";
  imgui_gl_ = true;
  return "";
}

void LiveWindow::activate() const {
  if (window_) glfwMakeContextCurrent(window_);
  if (imgui_) ImGui::SetCurrentContext(imgui_);
}

// Multisampling only on real GPUs: Mesa's software rasterizers (llvmpipe under Xvfb) shade
// every sample, so 4x would multiply the cost of filling the frame.
std::unique_ptr<render::Renderer> LiveWindow::create_renderer(int samples,
                                                              std::string* error) const {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  const char* gl_renderer = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
  const std::string renderer_name = gl_renderer ? gl_renderer : "";
  const bool software = renderer_name.find("llvmpipe") != std::string::npos ||
                        renderer_name.find("softpipe") != std::string::npos ||
                        renderer_name.find("swrast") != std::string::npos;
  const auto get_proc = reinterpret_cast<render::GlGetProcAddress>(glfwGetProcAddress);
  return render::Renderer::create(get_proc, std::max(fw, 1), std::max(fh, 1), error,
                                  samples > 0 ? samples : (software ? 1 : 4));
}

void LiveWindow::framebuffer_size(int* width, int* height) const {
  glfwGetFramebufferSize(window_, width, height);
}

double LiveWindow::pixel_scale() const {
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  return ww > 0 ? double(fw) / ww : 1.0;
}

float LiveWindow::default_ui_scale() const {
  float cx = 1.0f;
#ifndef __EMSCRIPTEN__
  float cy = 1.0f;
  glfwGetWindowContentScale(window_, &cx, &cy);
#endif
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  const float size = std::max(1.0f, std::min(w / 1280.0f, h / 720.0f));
  const float s = std::round(std::max(cx, 0.5f) * size * 4.0f) / 4.0f;
  return std::clamp(s, kMinUiScale, kMaxUiScale);
}

// The fonts: the embedded DejaVu Sans (Latin, Greek for mu, lambda, nu, a few symbols) at
// 16 px and the banners' 40 px, times the scale. Once the OpenGL3 backend has uploaded the
// font texture (the first frame does) it is uploaded again here.
ImFont* LiveWindow::set_ui_scale(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  if (glyph_ranges_.empty()) {
    ImFontGlyphRangesBuilder builder;
    builder.AddRanges(io.Fonts->GetGlyphRangesDefault());
    builder.AddText("μλνσψΨΔ≤≥·×−²∂∞→₁₂");  // the inspector: ∂P/∂F, +∞, σ₁
    builder.BuildRanges(&glyph_ranges_);
  }
  io.Fonts->Clear();
  ImFontConfig cfg;
  cfg.FontDataOwnedByAtlas = false;  // the bytes live in the executable
  void* font_data = const_cast<unsigned char*>(invfree_chart_font_begin);
  const int font_bytes = static_cast<int>(invfree_chart_font_end - invfree_chart_font_begin);
  io.Fonts->AddFontFromMemoryTTF(font_data, font_bytes, std::round(kFontSize * scale), &cfg,
                                 glyph_ranges_.Data);
  ImFont* big = io.Fonts->AddFontFromMemoryTTF(
      font_data, font_bytes, std::round(kBigFontSize * scale), &cfg, glyph_ranges_.Data);
  if (imgui_gl_ && imgui_frame_begun_) {
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
  }
  ImGui::GetStyle() = base_style_;
  ImGui::GetStyle().ScaleAllSizes(scale);
  return big;
}

bool LiveWindow::take_events(bool wait) {
  if (wait)
    glfwWaitEventsTimeout(kIdleWaitSeconds);
  else
    glfwPollEvents();
  const bool seen = input_seen_;
  input_seen_ = false;
  return seen;
}

void LiveWindow::begin_imgui_frame(const InputFrame* input) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  imgui_frame_begun_ = true;
  ImGuiIO& io = ImGui::GetIO();
  // The frames of one batch of input follow each other at once: ImGui needs time to pass.
  io.DeltaTime = std::max(io.DeltaTime, 1e-4f);
  if (input) apply_input_frame(*input, pointer_);
}

void LiveWindow::draw_imgui(int width, int height) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_.Viewport(0, 0, width, height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void LiveWindow::present() {
  glfwSwapBuffers(window_);
}

bool LiveWindow::should_close() const {
  return glfwWindowShouldClose(window_);
}

void LiveWindow::request_close() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void LiveWindow::set_fullscreen(bool on) {
#ifndef __EMSCRIPTEN__
  const bool is_on = glfwGetWindowMonitor(window_) != nullptr;
  if (on == is_on) return;
  if (on) {
    GLFWmonitor* monitor = glfwGetPrimaryMonitor();
    const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
    if (!mode) return;
    glfwGetWindowPos(window_, &windowed_[0], &windowed_[1]);
    glfwGetWindowSize(window_, &windowed_[2], &windowed_[3]);
    glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
  } else {
    glfwSetWindowMonitor(window_, nullptr, windowed_[0], windowed_[1], windowed_[2], windowed_[3],
                         0);
  }
#else
  (void)on;
#endif
}

void LiveWindow::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

}  // namespace invfree::live
