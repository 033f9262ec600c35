// Checks shared by the output tests: fresh temporary directories, complete OBJ and PNG
// files (no truncated file under a final name, no temporary left), one-line errors, a
// tiny tmpfs for full-disk tests, and waiting for a running command's files.
#pragma once

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>

#include "tests/reliability/process.h"

namespace invfree::test {

namespace fs = std::filesystem;

inline std::string fresh_dir(const std::string& name) {
  const std::string dir =
      ::testing::TempDir() + "/output_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline int count_lines_with_prefix(const std::string& text, const char* prefix) {
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

// Every file under `dir`: .obj files are complete meshes of `nodes` nodes and
// `triangles` triangles, and no temporary file is left. Returns the number of .obj files.
inline int expect_only_complete_objs(const std::string& dir, int nodes, int triangles) {
  int objs = 0;
  if (!fs::exists(dir)) return 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary file left behind: " << name;
    if (entry.path().extension() != ".obj") continue;
    ++objs;
    const std::string text = slurp(entry.path().string());
    EXPECT_FALSE(text.empty()) << name;
    EXPECT_EQ(text.back(), '\n') << name << " is truncated";
    EXPECT_EQ(count_lines_with_prefix(text, "v "), nodes) << name << " is truncated";
    EXPECT_EQ(count_lines_with_prefix(text, "f "), triangles) << name << " is truncated";
  }
  return objs;
}


// A tmpfs of `size` mounted at `dir` for the scope's lifetime, when this process may.
class TinyFilesystem {
 public:
  TinyFilesystem(const std::string& dir, const std::string& options) : dir_(dir) {
    fs::create_directories(dir);
    mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
    if (!mounted_) reason_ = std::strerror(errno);
  }
  ~TinyFilesystem() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  void remount_read_only() {
    ASSERT_EQ(::mount("tmpfs", dir_.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, nullptr), 0)
        << std::strerror(errno);
  }

 private:
  std::string dir_, reason_;
  bool mounted_ = false;
};

// Waits (at most 120 s) until `dir` holds at least `count` files ending in `extension`.
inline void wait_for_files(const std::string& dir, const std::string& extension, int count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  auto files = [&] {
    int n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) n += e.path().extension() == extension;
    return n;
  };
  while (files() < count && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

// Every PNG under `dir` is whole (signature first, IEND chunk last) and no temporary is
// left; returns the number of frames.
inline int expect_only_complete_pngs(const std::string& dir) {
  int frames = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary file left behind: " << name;
    if (entry.path().extension() != ".png") continue;
    ++frames;
    const std::string png = slurp(entry.path().string());
    EXPECT_GT(png.size(), 20u) << name;
    if (png.size() <= 20u) continue;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << name;
    EXPECT_EQ(png.substr(png.size() - 8), std::string("IEND\xae\x42\x60\x82", 8))
        << name << " is truncated";
  }
  return frames;
}

}  // namespace invfree::test
