#include "app/output_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace invfree {

std::string write_file_atomically(const std::string& path, std::string_view data) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return path + ": cannot create file: " + std::strerror(errno);
  size_t written = 0;
  while (written < data.size()) {
    const ssize_t n = ::write(fd, data.data() + written, data.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string err = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      return path + ": write failed: " + err;
    }
    written += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) {
    const std::string err = std::strerror(errno);
    ::unlink(tmp.c_str());
    return path + ": write failed: " + err;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string err = std::strerror(errno);
    ::unlink(tmp.c_str());
    return path + ": cannot rename into place: " + err;
  }
  return "";
}

std::string prepare_output_directory(const std::string& dir, bool must_be_empty, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) return dir + ": exists and is not a directory";
  fs::create_directories(dir, ec);
  if (ec) return dir + ": cannot create directory: " + ec.message();
  if (must_be_empty && !force && !fs::is_empty(dir, ec))
    return dir + ": directory is not empty (use --force to write into it anyway)";
  if (::access(dir.c_str(), W_OK) != 0) return dir + ": directory is not writable";
  return "";
}

}  // namespace invfree
