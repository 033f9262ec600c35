// The rules every output follows (docs/outputs.md), for every command:
// - A file is written under a temporary name in the same directory
//   ("<path>.tmp<pid>_<n>") and renamed over its final name only when complete, so a
//   reader, a crash, a full disk or Ctrl-C never leaves a truncated file under a final
//   name. Errors (full disk, file-size limit, unwritable directory) come back as one line
//   naming the path, and the temporary is removed.
// - Before a run, an output file must be a regular file or not exist (a device, FIFO,
//   socket or directory is refused, also through a symbolic link), must not be one of the
//   run's input files or its standard output or error (same device and inode), and its
//   directory is created if missing and must accept a new file.
// - A directory the run fills (simulate --obj, render --out, live --record) is created if
//   missing, locked for the whole run (flock on DIR/.invfree.lock, removed at the end;
//   a killed run leaves it behind, and it blocks nobody: the lock died with the process),
//   and must be empty (the lock file aside) unless --force.
#pragma once

#include <fcntl.h>

#include <string>
#include <string_view>
#include <vector>

namespace invfree {

// Why an output cannot be used: a bad choice of target (exit_code::kBadInput) or one that
// cannot be written (exit_code::kOutputFailed), with a one-line message naming the path.
// exit_code 0: no error.
struct OutputError {
  int exit_code = 0;
  std::string message;
  explicit operator bool() const { return exit_code != 0; }
};

// The descriptor of the OutputDirectory (below) open as `dir` (spelled as it was opened),
// or -1: for writers that cannot go through write_file_atomically (ffmpeg).
int output_directory_fd(const std::string& dir);

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
  std::string path_, name_, tmp_;  // name_ and tmp_: relative to dir_fd_
  int dir_fd_ = AT_FDCWD;          // or the descriptor of an OutputDirectory
  int fd_ = -1;
};

// Checks, before a long run, that `path` can be written later (the rules above); `inputs`
// are the paths of the files the run reads (names that do not exist are ignored).
OutputError check_output_file(const std::string& path, const std::vector<std::string>& inputs = {});

// An output named by an option, for check_outputs_apart's message.
struct NamedOutput {
  std::string option;  // e.g. "--csv"
  std::string path;
};

// Refuses (kBadInput), before a run, outputs that would collide at its end: a file that
// is also a directory the run fills, or lies above one (`--obj D --csv D`, `--obj D/sub
// --csv D`), or two file outputs that are one path. Paths are compared made absolute and
// normal, symbolic links of the parts that exist resolved. A file inside a directory the
// run fills (`--obj D --csv D/run.csv`) is fine.
OutputError check_outputs_apart(const std::vector<NamedOutput>& files,
                                const std::vector<NamedOutput>& dirs);

// A directory a run fills, held (locked) from open() until close() or destruction.
// Standard output carries each command's summary line through stdio's buffer, so a full
// disk or a file-size limit shows up only when it is flushed, and stdio keeps the error
// flag but not its reason. Commands flush with flush_standard_output(), which remembers
// the first failure's reason; main reports standard_output_error() (one line, or "")
// after the command, so a lost summary is never an exit 0.
void flush_standard_output();
std::string standard_output_error();  // flushes first

class OutputDirectory {
 public:
  static constexpr const char* kLockFile = ".invfree.lock";

  OutputDirectory() = default;
  ~OutputDirectory() { close(); }
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Creates `dir` if missing, locks it (another run holding it: kBadInput, naming its
  // pid), refuses it when it holds anything but the lock file unless `force`
  // (kBadInput), and checks that a file can be created in it (kOutputFailed).
  // The directory is opened once: files written into it by path while it is open
  // ("DIR/name" with DIR as given here: write_file_atomically, AtomicFileWriter) go
  // through that descriptor, so moving it or putting a symbolic link in its place during
  // the run changes nothing.
  OutputError open(const std::string& dir, bool force);
  void close();                       // removes the lock file and releases the lock
  int fd() const { return dir_fd_; }  // the directory's descriptor, -1 when not open

 private:
  OutputError open_and_lock(const std::string& dir, bool force);
  std::string lock_path_;
  int dir_fd_ = -1;
  int lock_fd_ = -1;
};

}  // namespace invfree
