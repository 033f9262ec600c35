// PNG frames written in the background: the renderer hands over a frame's pixels and goes
// on drawing the next one while worker threads encode (stb_image_write) and write it.
// Each file is written under a temporary name and renamed when complete
// (app/output_files.h), so a frame appears under its final name only whole.
//
// Inputs: RGBA8 pixels bottom row first (as Renderer::read_pixels gives them). Output:
// an 8-bit RGB PNG, top row first (alpha is dropped: frames are opaque).
// The queue is bounded (a few frames), so memory stays flat however long the movie.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace invfree::render {

// Encodes RGBA8 bottom-up pixels as an RGB PNG at zlib level `compression_level`
// (stb_image_write's scale: 1 fastest). Returns the file's bytes ("" on failure).
std::string encode_png(const std::uint8_t* rgba_bottom_up, int width, int height,
                       int compression_level);
// Encodes and writes atomically. Returns "" or a one-line error naming the path.
std::string write_png_file(const std::string& path, const std::uint8_t* rgba_bottom_up, int width,
                           int height, int compression_level);

class FrameWriter {
 public:
  FrameWriter(int threads, int compression_level, int queue_capacity = 4);
  ~FrameWriter();  // waits for the queued frames
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queues a frame; blocks while the queue is full. Returns false (and queues nothing)
  // once a write has failed: see error().
  bool submit(std::string path, int width, int height, std::vector<std::uint8_t> rgba_bottom_up);
  // A pixel buffer of an already written frame, to fill and submit again (empty when none
  // is free yet): recycling them saves allocating and page-faulting megabytes per frame.
  std::vector<std::uint8_t> take_buffer();
  // Waits until every queued frame is written; returns "" or the first error.
  std::string finish();
  std::string error() const;
  long written() const;

 private:
  struct Job {
    std::string path;
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;
  };
  void work();

  const int compression_level_;
  const size_t capacity_;
  const size_t thread_count_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  std::vector<std::vector<std::uint8_t>> free_buffers_;
  int busy_ = 0;
  bool stopping_ = false;
  long written_ = 0;
  std::string error_;
  std::vector<std::thread> threads_;
};

}  // namespace invfree::render
