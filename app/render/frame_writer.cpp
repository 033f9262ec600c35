#include "app/render/frame_writer.h"

#include <pthread.h>
#include <zlib.h>

#include <algorithm>
#include <cstdlib>

#include "app/output_files.h"

namespace {

// stb_image_write's own deflate is a simple one (fixed Huffman codes, short hash chains):
// slower than zlib at level 1 on these frames, and its files are larger. stb documents this hook
// (STBIW_ZLIB_COMPRESS); `quality` is stbi_write_png_compression_level. The buffer must come from
// malloc (stb frees it).
unsigned char* zlib_compress(unsigned char* data, int data_len, int* out_len, int quality) {
  uLongf size = compressBound(static_cast<uLong>(data_len));
  auto* out = static_cast<unsigned char*>(std::malloc(size));
  if (out == nullptr) return nullptr;
  if (compress2(out, &size, data, static_cast<uLong>(data_len), std::clamp(quality, 1, 9)) !=
      Z_OK) {
    std::free(out);
    return nullptr;
  }
  *out_len = static_cast<int>(size);
  return out;
}

}  // namespace

// stb_image_write compiled privately into this file (static functions and globals), so
// its settings here never affect another user of stb in the same program.
#define STBIW_ZLIB_COMPRESS zlib_compress
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace invfree::render {

namespace {

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<size_t>(size));
}

// stb reads its compression level from a global: set it once, before any worker starts,
// and never change it while one runs (all writers of a process use the first level).
std::once_flag g_level_once;

}  // namespace

std::string encode_png(const std::uint8_t* rgba, int width, int height, int compression_level) {
  std::call_once(g_level_once, [compression_level] {
    stbi_write_png_compression_level = std::max(1, compression_level);
    // The "up" filter for every row instead of trying all five per row: several times
    // faster and, on these flat-coloured figures, as small as the per-row best.
    stbi_write_force_png_filter = 2;
  });
  if (width <= 0 || height <= 0) return "";
  std::vector<std::uint8_t> rgb(static_cast<size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = rgba + static_cast<size_t>(height - 1 - y) * width * 4;
    std::uint8_t* dst = rgb.data() + static_cast<size_t>(y) * width * 3;
    for (int x = 0; x < width; ++x) {
      dst[3 * x] = src[4 * x];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
  std::string png;
  png.reserve(rgb.size() / 8);
  if (!stbi_write_png_to_func(append_bytes, &png, width, height, 3, rgb.data(), width * 3))
    return "";
  return png;
}

std::string write_png_file(const std::string& path, const std::uint8_t* rgba, int width, int height,
                           int compression_level) {
  const std::string png = encode_png(rgba, width, height, compression_level);
  if (png.empty()) return path + ": PNG encoding failed";
  return write_file_atomically(path, png);
}

FrameWriter::FrameWriter(int threads, int compression_level, int queue_capacity)
    : compression_level_(compression_level),
      capacity_(static_cast<size_t>(std::max(1, queue_capacity))),
      thread_count_(static_cast<size_t>(std::max(1, threads))) {
  for (size_t i = 0; i < thread_count_; ++i) threads_.emplace_back([this] { work(); });
}

FrameWriter::~FrameWriter() {
  finish();
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (auto& t : threads_) t.join();
}

bool FrameWriter::submit(std::string path, int width, int height, std::vector<std::uint8_t> rgba) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < capacity_ || !error_.empty(); });
  if (!error_.empty()) return false;
  queue_.push_back({std::move(path), width, height, std::move(rgba)});
  changed_.notify_all();
  return true;
}

std::vector<std::uint8_t> FrameWriter::take_buffer() {
  std::lock_guard lock(mutex_);
  if (free_buffers_.empty()) return {};
  std::vector<std::uint8_t> b = std::move(free_buffers_.back());
  free_buffers_.pop_back();
  return b;
}

std::string FrameWriter::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.empty() && busy_ == 0; });
  return error_;
}

std::string FrameWriter::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

long FrameWriter::written() const {
  std::lock_guard lock(mutex_);
  return written_;
}

void FrameWriter::work() {
  pthread_setname_np(pthread_self(), "invfree-png");  // for top and perf
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, nothing left
      job = std::move(queue_.front());
      queue_.pop_front();
      ++busy_;
    }
    changed_.notify_all();  // room in the queue
    bool skip = false;
    {
      std::lock_guard lock(mutex_);
      skip = !error_.empty();  // after a failure (disk full), write nothing more
    }
    const std::string e = skip ? ""
                               : write_png_file(job.path, job.pixels.data(), job.width, job.height,
                                                compression_level_);
    {
      std::lock_guard lock(mutex_);
      --busy_;
      if (free_buffers_.size() < capacity_ + thread_count_)
        free_buffers_.push_back(std::move(job.pixels));
      if (!skip && e.empty()) ++written_;
      if (!e.empty() && error_.empty()) error_ = e;
    }
    changed_.notify_all();
  }
}

}  // namespace invfree::render
