// Output that is never half-written: a file is written under a temporary name in the
// same directory and renamed over its final name only when complete, so a reader (or a
// crash, a full disk, Ctrl-C) never sees a truncated file under a final name.
#pragma once

#include <string>
#include <string_view>

namespace invfree {

// Writes `data` to `path` atomically. Returns "" or a one-line error naming the path.
std::string write_file_atomically(const std::string& path, std::string_view data);

// Creates `dir` (and parents) if missing. With `must_be_empty`, refuses a directory
// that already holds files unless `force`. Returns "" or a one-line error.
std::string prepare_output_directory(const std::string& dir, bool must_be_empty, bool force);

}  // namespace invfree
