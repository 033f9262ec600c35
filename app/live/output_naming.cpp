#include "app/live/output_naming.h"

#include <cstdio>
#include <filesystem>

namespace invfree::live {

std::string next_screenshot_path(const std::string& dir, int start) {
  const std::filesystem::path base = dir.empty() ? "." : dir;
  for (int n = std::max(start, 1);; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "invfree_%04d.png", n);
    std::error_code ec;
    const auto p = base / name;
    if (!std::filesystem::exists(p, ec)) return p.string();
  }
}

std::string record_frame_path(const std::string& dir, long frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06ld.png", frame);
  return (std::filesystem::path(dir.empty() ? "." : dir) / name).string();
}

}  // namespace invfree::live
