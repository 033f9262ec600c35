// The web build's FrameWriter (app/render/frame_writer.h): recording a PNG sequence needs
// a directory the user can open and zlib, neither of which the page has, so every frame is
// refused with a one-line reason. The live window then stops recording and shows that
// reason (LiveAppImpl::start_recording / stop_recording), as for a full disk on the desktop.
#include "app/render/frame_writer.h"

namespace invfree::render {

namespace {
constexpr const char* kUnavailable =
    "recording a PNG sequence is not available in the web page (use the desktop's `invfree "
    "live`)";
}

std::string encode_png(const std::uint8_t*, int, int, int) {
  return "";
}

std::string write_png_file(const std::string& path, const std::uint8_t*, int, int, int) {
  return path + ": " + kUnavailable;
}

FrameWriter::FrameWriter(int, int compression_level, int queue_capacity)
    : compression_level_(compression_level),
      capacity_(static_cast<size_t>(queue_capacity)),
      thread_count_(0) {
  error_ = kUnavailable;
}
FrameWriter::~FrameWriter() = default;

bool FrameWriter::submit(std::string, int, int, std::vector<std::uint8_t>) {
  return false;
}
std::vector<std::uint8_t> FrameWriter::take_buffer() {
  return {};
}
std::string FrameWriter::finish() {
  return error_;
}
std::string FrameWriter::error() const {
  return error_;
}
long FrameWriter::written() const {
  return 0;
}

}  // namespace invfree::render
