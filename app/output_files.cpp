#include "app/output_files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <utility>
#include <vector>

#include "app/exit_codes.h"

namespace invfree {

namespace {

// Unique per process and call, so two threads writing different frames never share one.
std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
}

std::string describe(int err) {
  std::string s = std::strerror(err);
  if (err == ENOSPC) s += " (disk full)";
  if (err == EFBIG) s += " (file-size limit reached)";
  return s;
}

// Writes all of `data` to `fd`, retrying short writes; returns 0 or an errno.
int write_all(int fd, std::string_view data) {
  size_t written = 0;
  while (written < data.size()) {
    const ssize_t n = ::write(fd, data.data() + written, data.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    written += static_cast<size_t>(n);
  }
  return 0;
}

// Creates and removes a file in `dir`: the only reliable writability test (access(2)
// says yes to root on a read-only mount's neighbour, and knows nothing of a full disk).
std::string probe_directory(const std::string& dir) {
  const std::string probe = temporary_name(dir + "/.invfree-probe");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return dir + ": cannot create files in this directory: " + describe(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

// The directories runs fill (OutputDirectory), each opened once: a file written into one
// by path ("DIR/name", DIR spelled as it was opened) is created and renamed relative to
// the directory's descriptor, so a directory moved or swapped for a symbolic link during
// the run still gets every file, and nothing lands where the new name points.
std::mutex g_directories_mutex;
std::vector<std::pair<std::string, int>> g_directories;  // (DIR as opened, its descriptor)

// Where a file is written: a directory descriptor (AT_FDCWD: none held) and the name
// relative to it.
struct Target {
  int dir_fd = AT_FDCWD;
  std::string name;
};

Target target_of(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash != std::string::npos && slash + 1 < path.size()) {
    const std::string dir = path.substr(0, slash), alt = path.substr(0, slash + 1);
    std::lock_guard lock(g_directories_mutex);
    for (const auto& [name, fd] : g_directories)
      if (name == dir || name == alt) return {fd, path.substr(slash + 1)};
  }
  return {AT_FDCWD, path};
}

}  // namespace

int output_directory_fd(const std::string& dir) {
  std::lock_guard lock(g_directories_mutex);
  for (const auto& [name, fd] : g_directories)
    if (name == dir) return fd;
  return -1;
}

std::string write_file_atomically(const std::string& path, std::string_view data) {
  const Target at = target_of(path);
  const std::string tmp = temporary_name(at.name);
  const int fd = ::openat(at.dir_fd, tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return path + ": cannot create file: " + describe(errno);
  if (const int err = write_all(fd, data); err != 0) {
    ::close(fd);
    ::unlinkat(at.dir_fd, tmp.c_str(), 0);
    return path + ": write failed: " + describe(err);
  }
  if (::close(fd) != 0) {  // NFS and some quota setups report a full disk only here
    const int err = errno;
    ::unlinkat(at.dir_fd, tmp.c_str(), 0);
    return path + ": write failed: " + describe(err);
  }
  if (::renameat(at.dir_fd, tmp.c_str(), at.dir_fd, at.name.c_str()) != 0) {
    const int err = errno;
    ::unlinkat(at.dir_fd, tmp.c_str(), 0);
    return path + ": cannot rename into place: " + describe(err);
  }
  return "";
}

AtomicFileWriter::~AtomicFileWriter() {
  abandon();
}

void AtomicFileWriter::abandon() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlinkat(dir_fd_, tmp_.c_str(), 0);
  fd_ = -1;
}

std::string AtomicFileWriter::open(const std::string& path) {
  abandon();
  path_ = path;
  const Target at = target_of(path);
  dir_fd_ = at.dir_fd;
  name_ = at.name;
  tmp_ = temporary_name(at.name);
  fd_ = ::openat(dir_fd_, tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) return path + ": cannot create file: " + describe(errno);
  return "";
}

std::string AtomicFileWriter::append(std::string_view data) {
  if (fd_ < 0) return path_ + ": not open";
  if (const int err = write_all(fd_, data); err != 0) {
    abandon();
    return path_ + ": write failed: " + describe(err);
  }
  return "";
}

std::string AtomicFileWriter::commit() {
  if (fd_ < 0) return path_ + ": not open";
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlinkat(dir_fd_, tmp_.c_str(), 0);
    return path_ + ": write failed: " + describe(err);
  }
  if (::renameat(dir_fd_, tmp_.c_str(), dir_fd_, name_.c_str()) != 0) {
    const int err = errno;
    ::unlinkat(dir_fd_, tmp_.c_str(), 0);
    return path_ + ": cannot rename into place: " + describe(err);
  }
  return "";
}

namespace {

OutputError bad_input(const std::string& message) {
  return {exit_code::kBadInput, message};
}
OutputError cannot_write(const std::string& message) {
  return {exit_code::kOutputFailed, message};
}

bool same_file(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

const char* kind_of(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Creates `dir` and its parents if missing; "" or an error naming `what`.
std::string create_directory(const std::string& dir, const std::string& what) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    return what + ": cannot create directory" + (what == dir ? "" : " " + dir) + ": " +
           ec.message();
  return "";
}

// An existing DIR/.invfree.lock is used (locked, its pid rewritten) only when it is what
// a run leaves: a regular file with a single link, holding nothing or a pid line.
OutputError check_lock_file(int fd, const std::string& lock_path) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) return cannot_write(lock_path + ": " + describe(errno));
  const std::string advice =
      "; not used as this directory's lock (remove it, or choose another directory)";
  if (!S_ISREG(st.st_mode)) return bad_input(lock_path + ": is " + kind_of(st.st_mode) + advice);
  if (st.st_nlink != 1)
    return bad_input(lock_path + ": is a hard link to another file (" +
                     std::to_string(st.st_nlink) + " names)" + advice);
  char text[40] = {};
  const ssize_t n =
      st.st_size < static_cast<off_t>(sizeof text) ? ::pread(fd, text, sizeof text, 0) : -1;
  bool pid_line = n >= 0;
  for (ssize_t i = 0; pid_line && i < n; ++i)
    pid_line = (text[i] >= '0' && text[i] <= '9') || (text[i] == '\n' && i + 1 == n);
  if (!pid_line)
    return bad_input(lock_path + ": is not an invfree lock file (it holds other data)" + advice);
  return {};
}

}  // namespace

namespace {
int g_stdout_errno = 0;  // the first failed flush's errno (main thread only)
}  // namespace

void flush_standard_output() {
  errno = 0;
  if (std::fflush(stdout) != 0 && g_stdout_errno == 0) g_stdout_errno = errno;
}

std::string standard_output_error() {
  flush_standard_output();
  if (!std::ferror(stdout) && g_stdout_errno == 0) return "";
  return std::string("standard output: write failed") +
         (g_stdout_errno != 0 ? std::string(": ") + describe(g_stdout_errno) : std::string()) +
         "; the summary is lost";
}

OutputError check_output_file(const std::string& path, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  if (path.empty()) return bad_input("output file: empty path");
  if (path.back() == '/') return bad_input(path + ": names a directory; give a file name");
  if (path == "-")
    return bad_input(
        "-: an output file cannot be standard output (it carries the summary line); give a file "
        "name");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {  // follows symbolic links: the target is judged
    if (S_ISDIR(st.st_mode)) return bad_input(path + ": is a directory");
    if (!S_ISREG(st.st_mode))
      return bad_input(path + ": is " + kind_of(st.st_mode) +
                       "; an output must be a regular file or not exist yet");
    for (const std::string& input : inputs) {
      struct stat in {};
      if (::stat(input.c_str(), &in) == 0 && same_file(in, st))
        return bad_input(path + ": is the input file " + input +
                         "; an output never replaces an input");
    }
    for (const int fd : {STDOUT_FILENO, STDERR_FILENO}) {
      struct stat stream {};
      if (::fstat(fd, &stream) == 0 && same_file(stream, st))
        return bad_input(path + ": is this command's standard " +
                         (fd == STDOUT_FILENO ? "output" : "error") + "; give another file name");
    }
  }
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  std::error_code ec;
  const fs::file_status parent_status = fs::status(parent, ec);
  if (!fs::exists(parent_status)) {
    if (auto e = create_directory(parent.string(), path); !e.empty()) return cannot_write(e);
  } else if (!fs::is_directory(parent_status)) {
    return cannot_write(path + ": " + parent.string() + " is not a directory");
  }
  if (auto e = probe_directory(parent.string()); !e.empty()) return cannot_write(path + ": " + e);
  return {};
}

namespace {

// `path` absolute and normal, with the links of its existing part resolved; no trailing
// separator.
std::filesystem::path comparable_path(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) p = fs::absolute(path, ec).lexically_normal();
  std::string text = p.string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

// Whether `inner` is `outer` or lies below it.
bool within(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

}  // namespace

OutputError check_outputs_apart(const std::vector<NamedOutput>& files,
                                const std::vector<NamedOutput>& dirs) {
  for (size_t i = 0; i < files.size(); ++i) {
    if (files[i].path.empty()) continue;
    const auto file = comparable_path(files[i].path);
    for (const NamedOutput& d : dirs) {
      if (d.path.empty() || !within(comparable_path(d.path), file)) continue;
      return bad_input(
          files[i].option + " " + files[i].path + " and " + d.option + " " + d.path +
          ": the file would be " +
          (comparable_path(d.path) == file ? "the directory itself" : "a directory above it") +
          "; give them different paths");
    }
    for (size_t j = i + 1; j < files.size(); ++j)
      if (!files[j].path.empty() && comparable_path(files[j].path) == file)
        return bad_input(files[i].option + " " + files[i].path + " and " + files[j].option + " " +
                         files[j].path + ": the same file; give them different paths");
  }
  return {};
}

OutputError OutputDirectory::open(const std::string& dir, bool force) {
  close();
  OutputError e = open_and_lock(dir, force);
  if (e) {
    close();
    return e;
  }
  std::lock_guard lock(g_directories_mutex);
  g_directories.emplace_back(dir, dir_fd_);
  return {};
}

OutputError OutputDirectory::open_and_lock(const std::string& dir, bool force) {
  namespace fs = std::filesystem;
  if (dir.empty()) return bad_input("output directory: empty path");
  struct stat st {};
  if (::stat(dir.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) return bad_input(dir + ": exists and is not a directory");
  } else if (auto e = create_directory(dir, dir); !e.empty()) {
    return cannot_write(e);
  }
  dir_fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd_ < 0) return cannot_write(dir + ": cannot open directory: " + describe(errno));
  // Anything but the lock file: refused without --force.
  auto refuse_non_empty = [&]() -> OutputError {
    if (force) return {};
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it->path().filename() != kLockFile)
        return bad_input(dir + ": directory is not empty (use --force to write into it anyway)");
    if (ec) return cannot_write(dir + ": cannot list directory: " + ec.message());
    return {};
  };
  // The lock file of a run that was killed is used as it is; a new one is created only in
  // a directory that passes the emptiness check, so a refused directory gets none.
  // O_NOFOLLOW: never truncate a file elsewhere through a planted link. The holder
  // removes the file when it is done (close()), so a lock taken on a file that was
  // removed in the meantime does not count: then try again with the new one.
  // An existing lock file is written into (our pid) only when it is one: a regular file
  // with one link holding at most a pid line. Anything else under that name (a hard link
  // to another file, e.g. the scene being read, or a file with other content) is refused
  // and left untouched.
  lock_path_ = dir + "/" + kLockFile;
  for (int attempt = 0; lock_fd_ < 0; ++attempt) {
    int fd = ::openat(dir_fd_, kLockFile, O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd >= 0) {
      if (auto e = check_lock_file(fd, lock_path_)) {
        ::close(fd);
        return e;
      }
    } else {
      if (auto e = refuse_non_empty()) return e;
      fd = ::openat(dir_fd_, kLockFile, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
      if (fd < 0 && errno == EEXIST && attempt < 10) continue;  // another run made it just now
    }
    if (fd < 0)
      return cannot_write(dir + ": cannot create files in this directory: " + describe(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
      char holder[32] = {};
      const ssize_t n = ::pread(fd, holder, sizeof holder - 1, 0);
      ::close(fd);
      const long pid = n > 0 ? std::strtol(holder, nullptr, 10) : 0;
      return bad_input(dir + ": another invfree run is writing into this directory" +
                       (pid > 0 ? " (pid " + std::to_string(pid) + ")" : std::string()) +
                       "; wait for it to end or choose another directory");
    }
    // (Another flock error: a filesystem without locks; the run goes on unlocked.)
    struct stat held {
    }, named{};
    if ((::fstat(fd, &held) == 0 &&
         ::fstatat(dir_fd_, kLockFile, &named, AT_SYMLINK_NOFOLLOW) == 0 &&
         same_file(held, named)) ||
        attempt == 10) {
      lock_fd_ = fd;
    } else {
      ::close(fd);
    }
  }
  const int fd = lock_fd_;
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, pid.data(), pid.size(), 0);
  if (auto e = refuse_non_empty()) return e;  // checked again now that no other run can write
  if (auto e = probe_directory(dir); !e.empty()) return cannot_write(e);
  return {};
}

void OutputDirectory::close() {
  if (dir_fd_ < 0) return;
  {
    std::lock_guard lock(g_directories_mutex);
    for (auto it = g_directories.begin(); it != g_directories.end(); ++it)
      if (it->second == dir_fd_) {
        g_directories.erase(it);
        break;
      }
  }
  if (lock_fd_ >= 0) {
    // Removed while still held, and only if it is still ours (see open()).
    struct stat held {
    }, named{};
    if (::fstat(lock_fd_, &held) == 0 &&
        ::fstatat(dir_fd_, kLockFile, &named, AT_SYMLINK_NOFOLLOW) == 0 && same_file(held, named))
      ::unlinkat(dir_fd_, kLockFile, 0);
    ::close(lock_fd_);  // releases the flock
    lock_fd_ = -1;
  }
  ::close(dir_fd_);
  dir_fd_ = -1;
}

}  // namespace invfree
