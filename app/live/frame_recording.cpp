#include "app/live/frame_recording.h"

#include <cstdio>
#include <filesystem>

#include "app/live/output_naming.h"
#include "app/live/window_capture.h"

namespace invfree::live {

namespace {

constexpr int kPngCompression = 1;  // zlib's fastest level

}  // namespace

bool FrameRecording::start(const std::string& dir, bool force, const Say& say) {
  if (const OutputError e = output_.open(dir, force)) {
    say("invfree: live: cannot record: " + e.message);
    return false;
  }
  writer_ = std::make_unique<render::FrameWriter>(1, kPngCompression);
  dir_ = dir;
  frame_ = 0;
  say("recording to " + record_frame_path(dir, 0) + " ...");
  return true;
}

void FrameRecording::stop(const Say& say) {
  if (!writer_) return;
  const std::string e = writer_->finish();
  const long n = writer_->written();
  writer_.reset();
  output_.close();
  if (!e.empty()) say("invfree: live: recording failed: " + e);
  say("recorded " + std::to_string(n) + " frame(s) to " + dir_);
}

bool FrameRecording::add(long revision, const render::GlApi& gl, int width, int height) {
  if (!writer_ || revision == added_revision_) return true;
  added_revision_ = revision;
  if (!writer_->submit(record_frame_path(dir_, frame_), width, height,
                       read_window_bottom_up(gl, width, height)))
    return false;
  ++frame_;
  return true;
}

std::string new_recording_dir(const std::string& preferred, const std::string& screenshot_dir) {
  if (!preferred.empty() && !std::filesystem::exists(preferred)) return preferred;
  const std::filesystem::path base = screenshot_dir.empty() ? "." : screenshot_dir;
  for (int n = 1;; ++n) {
    char name[40];
    std::snprintf(name, sizeof name, "invfree_recording_%04d", n);
    if (!std::filesystem::exists(base / name)) return (base / name).string();
  }
}

}  // namespace invfree::live
