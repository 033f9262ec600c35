// The live window's PNG-sequence recording (Ctrl+R, the Record button, --record): each new
// state the window shows, once, as DIR/frame_NNNNNN.png (output_naming.h, the naming of
// `invfree render`). A background writer compresses at zlib's fastest level, so that
// recording keeps up with the window; the directory is locked while recording.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "app/output_files.h"
#include "app/render/frame_writer.h"
#include "app/render/gl_api.h"

namespace invfree::live {

class FrameRecording {
 public:
  using Say = std::function<void(const std::string&)>;  // a line for the user

  // Starts recording into `dir` (with `force` it may hold files already). False, having
  // said why, when the directory cannot be used.
  bool start(const std::string& dir, bool force, const Say& say);
  // Waits for the queued frames and says how many were written where.
  void stop(const Say& say);
  bool active() const { return writer_ != nullptr; }
  // The window's back buffer (width x height) as the next frame, unless it shows the state
  // added last (`revision`: LiveController::revision). False when the writer has failed.
  bool add(long revision, const render::GlApi& gl, int width, int height);

 private:
  std::unique_ptr<render::FrameWriter> writer_;
  OutputDirectory output_;
  std::string dir_;
  long frame_ = 0;
  long added_revision_ = -1;
};

// A directory for a new recording: `preferred` while it does not exist yet, else the first
// DIR/invfree_recording_NNNN that does not, beside the screenshots (DIR: `screenshot_dir`,
// or "." when empty).
std::string new_recording_dir(const std::string& preferred, const std::string& screenshot_dir);

}  // namespace invfree::live
