#include "app/output_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

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

}  // namespace

std::string write_file_atomically(const std::string& path, std::string_view data) {
  const std::string tmp = temporary_name(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return path + ": cannot create file: " + describe(errno);
  if (const int err = write_all(fd, data); err != 0) {
    ::close(fd);
    ::unlink(tmp.c_str());
    return path + ": write failed: " + describe(err);
  }
  if (::close(fd) != 0) {  // NFS and some quota setups report a full disk only here
    const int err = errno;
    ::unlink(tmp.c_str());
    return path + ": write failed: " + describe(err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
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
  ::unlink(tmp_.c_str());
  fd_ = -1;
}

std::string AtomicFileWriter::open(const std::string& path) {
  abandon();
  path_ = path;
  tmp_ = temporary_name(path);
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
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
    ::unlink(tmp_.c_str());
    return path_ + ": write failed: " + describe(err);
  }
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    return path_ + ": cannot rename into place: " + describe(err);
  }
  return "";
}

std::string prepare_output_directory(const std::string& dir, bool must_be_empty, bool force,
                                     bool* refused_non_empty) {
  namespace fs = std::filesystem;
  if (refused_non_empty) *refused_non_empty = false;
  if (dir.empty()) return "output directory: empty path";
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st) && !fs::is_directory(st)) return dir + ": exists and is not a directory";
  if (!fs::exists(st)) {
    fs::create_directories(dir, ec);
    if (ec) return dir + ": cannot create directory: " + ec.message();
  }
  if (must_be_empty && !force) {
    const bool empty = fs::is_empty(dir, ec);
    if (ec) return dir + ": cannot list directory: " + ec.message();
    if (!empty) {
      if (refused_non_empty) *refused_non_empty = true;
      return dir + ": directory is not empty (use --force to write into it anyway)";
    }
  }
  return probe_directory(dir);
}

std::string check_output_file(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) return "output file: empty path";
  std::error_code ec;
  if (fs::is_directory(path, ec)) return path + ": is a directory";
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  const fs::file_status st = fs::status(parent, ec);
  if (!fs::exists(st)) {
    fs::create_directories(parent, ec);
    if (ec) return path + ": cannot create directory " + parent.string() + ": " + ec.message();
  } else if (!fs::is_directory(st)) {
    return path + ": " + parent.string() + " is not a directory";
  }
  if (auto e = probe_directory(parent.string()); !e.empty()) return path + ": " + e;
  return "";
}

}  // namespace invfree
