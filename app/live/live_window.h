// The live window's platform side: one GLFW window with its OpenGL 3.3 core context (GL
// loaded into a GlApi, app/render/gl_api.h), Dear ImGui's context with its GLFW and
// OpenGL3 backends, ImGui's fonts and style at the UI scale, and the wake-up of the idle
// wait when input arrives.
// Several windows may exist at once (tests): each keeps its own GL and ImGui contexts, made
// current by activate(), and GLFW's callbacks find their window through its user pointer.
#pragma once

#include <imgui.h>

#include <memory>
#include <string>

#include "app/live/input_queue.h"
#include "app/render/gl_api.h"

struct GLFWwindow;

namespace invfree::render {
class Renderer;
}

namespace invfree::live {

class LiveWindow {
 public:
  LiveWindow() = default;
  ~LiveWindow();
  LiveWindow(const LiveWindow&) = delete;  // GLFW's callbacks hold its address
  LiveWindow& operator=(const LiveWindow&) = delete;

  // Opens the window with a current OpenGL 3.3 core context and loads GL from it. Returns
  // "" or why not.
  std::string open(int width, int height, bool vsync);
  // Dear ImGui on the window: its context (writing no files), style and backends; the fonts
  // come with the first set_ui_scale. After open(). Returns "" or why not.
  std::string start_imgui();
  void activate() const;
  // The shared renderer on this window's context, at its framebuffer size, with `samples`
  // per pixel (0: 4, or 1 on a software rasterizer). Null with *error when it cannot start.
  std::unique_ptr<render::Renderer> create_renderer(int samples, std::string* error) const;

  GLFWwindow* glfw() const { return window_; }
  const render::GlApi& gl() const { return gl_; }
  void framebuffer_size(int* width, int* height) const;
  // Framebuffer pixels per window coordinate (1 except on HiDPI screens).
  double pixel_scale() const;
  // The UI scale the window starts with: its content scale (HiDPI) times how much larger
  // than 1280x720 it is (never smaller), in steps of 0.25: 1 at 1280x720, 1.5 at 1920x1080.
  float default_ui_scale() const;
  // ImGui's fonts rebuilt at `scale` (sharp, not stretched) and its spacing scaled. Between
  // ImGui frames only. Returns the banners' large font.
  ImFont* set_ui_scale(float scale);

  // The events since the last call; with `wait`, waits for one first (a short while at most,
  // so that Ctrl-C and --frames still end the run). Returns whether input arrived.
  bool take_events(bool wait);
  // The input events since the last call, in the ImGui frames they need (input_queue.h).
  std::vector<InputFrame> take_input() { return queue_.take(); }
  // The backends' part of a new ImGui frame (the font texture, the frame's time; the
  // pointer as the system has it now), then `input`'s events (null: a test's Injection
  // follows instead); ImGui::NewFrame next.
  void begin_imgui_frame(const InputFrame* input);
  // ImGui's draw data over the window's back buffer (framebuffer size width x height).
  void draw_imgui(int width, int height);
  void present();
  bool should_close() const;
  void request_close();
  void set_title(const std::string& title);
  // The window on the whole primary monitor, or back to where and how large it was. The
  // browser's page cannot (its F11 can): there it does nothing.
  void set_fullscreen(bool on);

 private:
  static void note_input(GLFWwindow* window);  // from GLFW's callbacks
  static void queue_input(GLFWwindow* window, const InputEvent& e);

  GLFWwindow* window_ = nullptr;
  render::GlApi gl_;
  ImGuiContext* imgui_ = nullptr;
  bool imgui_glfw_ = false, imgui_gl_ = false;
  bool imgui_frame_begun_ = false;  // the OpenGL3 backend has uploaded the font texture
  ImGuiStyle base_style_;           // the style at UI scale 1
  ImVector<ImWchar> glyph_ranges_;  // the fonts' characters; the atlas reads them when built
  bool input_seen_ = false;
  InputQueue queue_;
  int windowed_[4] = {0, 0, 0, 0};  // x, y, width, height before full screen
  PointerState pointer_;
};

}  // namespace invfree::live
