// File names of the live window's outputs.
//  - screenshots: DIR/invfree_NNNN.png, numbered from 1, never overwriting an existing file;
//  - recordings: DIR/frame_000000.png, DIR/frame_000001.png, ... (the naming of
//    `invfree render`, so the same tools, e.g. ffmpeg -i DIR/frame_%06d.png, take both).
#pragma once

#include <string>

namespace invfree::live {

// The first DIR/invfree_NNNN.png (NNNN >= `start`) that does not exist yet.
std::string next_screenshot_path(const std::string& dir, int start = 1);

std::string record_frame_path(const std::string& dir, long frame);

}  // namespace invfree::live
