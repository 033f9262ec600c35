// How the scene picker names a scene: a built-in scene by its name, a scene file by its
// file name (a path does not fit the picker; the full path is in its tooltip).
#pragma once

#include <filesystem>
#include <string>

namespace invfree::live {

inline std::string scene_display_name(const std::string& label) {
  if (label.find('/') == std::string::npos) return label;
  const std::string name = std::filesystem::path(label).filename().string();
  return name.empty() ? label : name;
}

}  // namespace invfree::live
