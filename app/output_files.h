// Output that is never half-written: a file is written under a temporary name in the
// same directory ("<path>.tmp<pid>_<n>") and renamed over its final name only when
// complete, so a reader, a crash, a full disk or Ctrl-C never leaves a truncated file
// under a final name. Errors (full disk, file-size limit, unwritable or missing
// directory) come back as one line naming the path, and the temporary is removed.
#pragma once

#include <string>
#include <string_view>

namespace invfree {

// Writes `data` to `path` atomically. Returns "" or a one-line error naming the path.
std::string write_file_atomically(const std::string& path, std::string_view data);

// A file written incrementally (e.g. a CSV row per step, so a long run keeps flat memory)
// and still atomically: it lives under the temporary name until commit() renames it; if
// commit() is never called (an error, an exception) the destructor removes it.
class AtomicFileWriter {
 public:
  AtomicFileWriter() = default;
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  std::string open(const std::string& path);  // "" or a one-line error
  std::string append(std::string_view data);  // "" or a one-line error
  std::string commit();                       // closes and renames; "" or an error
  bool is_open() const { return fd_ >= 0; }

 private:
  void abandon();
  std::string path_, tmp_;
  int fd_ = -1;
};

// Creates `dir` (and parents) if missing and checks that a file can be created in it.
// With `must_be_empty`, refuses a directory that already holds files unless `force`
// (then sets *refused_non_empty, so the caller can report it as bad input rather than
// as an output failure). Returns "" or a one-line error.
std::string prepare_output_directory(const std::string& dir, bool must_be_empty, bool force,
                                     bool* refused_non_empty = nullptr);

// Checks, before a long run, that `path` can be written later: not a directory, and its
// directory (created if missing) accepts a new file. Returns "" or a one-line error.
std::string check_output_file(const std::string& path);

}  // namespace invfree
