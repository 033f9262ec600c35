// `invfree live`'s loop around one LiveApp (live_app.h): frames until the window closes,
// the frame count is reached or the caller stops it, then the final screenshot, the
// benchmark line (with the CPU time of the picture's capture and of the inspector's
// windows per frame), and the exit code (a failed step under --frames is a failed run).
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "app/exit_codes.h"
#include "app/live/live_app.h"

namespace invfree::live {

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
    const LiveApp::PartTimes parts = app->part_times();
    const double per_frame = 1.0 / std::max<long>(1, frames);
    std::printf(
        "live bench: %ld frames in %.2f s = %.1f frames/s (scene %s, n_seg %d, h %g, %d "
        "step(s)/frame; %ld steps, "
        "%.2f ms/step, %.2f ms/frame; capture %.3f ms/frame, inspector %.3f ms/frame of CPU)\n",
        frames, seconds, frames / seconds, s.name.c_str(), s.n_seg, s.h, lc.steps_per_frame, steps,
        steps ? lc.step_ms_total() / steps : 0.0, 1e3 * seconds * per_frame,
        parts.capture_ms * per_frame, parts.inspection_ms * per_frame);
  }
  if (!lc.banner.empty()) {
    std::fprintf(stderr, "invfree: live: %s\n", lc.banner.c_str());
    if (options.frames > 0) return exit_code::kRunFailed;
  }
  return exit_code::kOk;
}

}  // namespace invfree::live
