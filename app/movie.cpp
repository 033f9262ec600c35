// See movie.h.
#include "app/movie.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "app/interrupt.h"
#include "app/output_files.h"

namespace invfree {

std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::string candidate = dir + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate))
      return candidate;
    start = end + 1;
  }
  return "";
}

namespace {

// A file read at offsets through a 64 KiB window: movies can be large, so they are
// walked, never loaded.
class FileBytes {
 public:
  explicit FileBytes(int fd) : fd_(fd) {
    struct stat st {};
    size_ = ::fstat(fd, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
  }
  std::uint64_t size() const { return size_; }
  // The byte at `at` (< size()), or -1 when it cannot be read.
  int at(std::uint64_t at) {
    if (at < start_ || at >= start_ + window_.size()) {
      window_.resize(1 << 16);
      ssize_t n;
      do n = ::pread(fd_, window_.data(), window_.size(), static_cast<off_t>(at));
      while (n < 0 && errno == EINTR);
      window_.resize(n > 0 ? static_cast<size_t>(n) : 0);
      start_ = at;
      if (window_.empty()) return -1;
    }
    return window_[at - start_];
  }
  // `bytes` bytes from `at`, big-endian; false when they cannot be read.
  bool big_endian(std::uint64_t at, int bytes, std::uint64_t* value) {
    *value = 0;
    for (int i = 0; i < bytes; ++i) {
      const int b = this->at(at + i);
      if (b < 0) return false;
      *value = (*value << 8) | static_cast<unsigned>(b);
    }
    return true;
  }

 private:
  int fd_;
  std::uint64_t size_ = 0, start_ = 0;
  std::vector<unsigned char> window_;
};

// The boxes of an MP4 between [begin, end): calls visit(type, body_begin, body_end) for
// each; false when a box is cut short or malformed.
template <class Visit>
bool walk_boxes(FileBytes& file, std::uint64_t begin, std::uint64_t end, Visit&& visit) {
  for (std::uint64_t at = begin; at < end;) {
    std::uint64_t size = 0, type = 0;
    if (end - at < 8 || !file.big_endian(at, 4, &size) || !file.big_endian(at + 4, 4, &type))
      return false;
    std::uint64_t header = 8;
    if (size == 1) {
      if (end - at < 16 || !file.big_endian(at + 8, 8, &size)) return false;
      header = 16;
    } else if (size == 0) {
      size = end - at;  // to the end
    }
    if (size < header || size > end - at) return false;
    std::string name(4, ' ');
    for (int i = 0; i < 4; ++i) name[i] = static_cast<char>((type >> (24 - 8 * i)) & 0xff);
    if (!visit(name, at + header, at + size)) return false;
    at += size;
  }
  return true;
}

std::string check_mp4(FileBytes& file, int frames) {
  bool ftyp = false, moov = false, mdat = false;
  std::uint64_t samples = 0;
  bool have_samples = false;
  std::function<bool(const std::string&, std::uint64_t, std::uint64_t)> visit =
      [&](const std::string& type, std::uint64_t b, std::uint64_t e) {
        if (type == "ftyp") ftyp = true;
        if (type == "mdat") mdat = true;
        if (type == "moov") moov = true;
        if (type == "moov" || type == "trak" || type == "mdia" || type == "minf" || type == "stbl")
          return walk_boxes(file, b, e, visit);
        // stsz: version and flags (4), sample_size (4), sample_count (4).
        if (type == "stsz" && e - b >= 12 && !have_samples)
          have_samples = file.big_endian(b + 8, 4, &samples);
        return true;
      };
  if (!walk_boxes(file, 0, file.size(), visit))
    return "a box is cut short (" + std::to_string(file.size()) + " bytes)";
  if (!ftyp || !mdat) return "no ftyp or mdat box";
  if (!moov) return "no moov box, the index ffmpeg writes last";
  if (!have_samples || samples != static_cast<std::uint64_t>(frames))
    return "its video track holds " + std::to_string(samples) + " of " + std::to_string(frames) +
           " frames";
  return "";
}

// GIF: header, logical screen descriptor (+ global colour table), then extension blocks
// (0x21), images (0x2C) and the trailer (0x3B), which must be the last byte.
std::string check_gif(FileBytes& file) {
  const std::uint64_t n = file.size();
  std::string magic;
  for (int i = 0; i < 6 && i < static_cast<int>(n); ++i) magic += static_cast<char>(file.at(i));
  if (n < 13 || (magic != "GIF87a" && magic != "GIF89a")) return "no GIF header";
  std::uint64_t at = 13;
  const int screen_flags = file.at(10);
  if (screen_flags & 0x80) at += 3u << ((screen_flags & 7) + 1);
  // Data sub-blocks: a length byte and that many bytes, up to a zero length.
  auto skip_sub_blocks = [&]() {
    for (int len; at < n && (len = file.at(at)) != 0;) {
      if (len < 0) return false;
      at += 1 + static_cast<unsigned>(len);
    }
    if (at >= n) return false;
    ++at;
    return true;
  };
  int images = 0;
  while (at < n) {
    const int block = file.at(at++);
    if (block == 0x3B) {
      if (at != n) return "data after its trailer";
      if (images == 0) return "no image";
      return "";
    }
    if (block == 0x21) {
      if (++at >= n || !skip_sub_blocks()) break;  // the label, then its data
    } else if (block == 0x2C) {
      if (n - at < 10) break;
      const int flags = file.at(at + 8);
      at += 9;
      if (flags & 0x80) at += 3u << ((flags & 7) + 1);
      if (++at >= n || !skip_sub_blocks()) break;  // LZW minimum code size, then the data
      ++images;
    } else {
      return block < 0 ? "it cannot be read" : "an unknown block";
    }
  }
  return "no trailer: it is cut short after " + std::to_string(images) + " images";
}

// Checks the movie `name` relative to `dir_fd` (check_movie_file); *size: its bytes.
std::string check_movie_at(int dir_fd, const std::string& name, bool gif, int frames,
                           std::uint64_t* size = nullptr) {
  const int fd = ::openat(dir_fd, name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "it cannot be read";
  FileBytes file(fd);
  std::string why = file.size() == 0 ? "it is empty"
                    : gif            ? check_gif(file)
                                     : check_mp4(file, frames);
  if (size) *size = file.size();
  ::close(fd);
  return why;
}

// Why a file of `size` bytes that ffmpeg wrote into the directory `dir_fd` came out
// incomplete, when it can be told: its size at the file-size limit, or no room left on
// its filesystem. "" otherwise.
std::string likely_write_failure(int dir_fd, const std::string& name, std::uint64_t size) {
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      static_cast<rlim_t>(size) + 65536 >= limit.rlim_cur)
    return "File too large (file-size limit reached)";
  const int fd = ::openat(dir_fd, name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "";
  struct statvfs fs {};
  const bool full =
      ::fstatvfs(fd, &fs) == 0 && static_cast<double>(fs.f_bavail) * fs.f_frsize < (1 << 20);
  ::close(fd);
  return full ? "No space left on device (disk full)" : "";
}

}  // namespace

std::string check_movie_file(const std::string& path, bool gif, int frames) {
  return check_movie_at(AT_FDCWD, path, gif, frames);
}

std::string make_movie(const std::string& ffmpeg, const std::string& dir, int frames, double fps,
                       bool gif, const std::function<void(int)>& on_frame, bool* made,
                       const std::string& movie_path) {
  *made = false;
  const std::string ext = gif ? "gif" : "mp4";
  const std::string final_path = movie_path.empty() ? dir + "/movie." + ext : movie_path;
  // Into the run's output directory through the descriptor it was opened with
  // (output_files.h): ffmpeg runs in it, and the checks and the rename are relative to it.
  const int dir_fd = movie_path.empty() ? output_directory_fd(dir) : -1;
  const int at = dir_fd >= 0 ? dir_fd : AT_FDCWD;
  const std::string final_name = dir_fd >= 0 ? "movie." + ext : final_path;
  // Beside the final name (the rename stays within its directory): "<stem>.tmp<pid>.<ext>".
  const size_t dot = final_name.rfind('.'), slash = final_name.rfind('/');
  const std::string stem = dot != std::string::npos && (slash == std::string::npos || dot > slash)
                               ? final_name.substr(0, dot)
                               : final_name;
  const std::string tmp = stem + ".tmp" + std::to_string(::getpid()) + "." + ext;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {ffmpeg,
                                   "-nostdin",
                                   "-y",
                                   "-loglevel",
                                   "error",
                                   "-progress",
                                   "pipe:1",
                                   "-framerate",
                                   rate,
                                   "-i",
                                   dir_fd >= 0 ? "frame_%06d.png" : dir + "/frame_%06d.png",
                                   "-frames:v",
                                   std::to_string(frames)};
  const std::vector<std::string> mp4_args = {
      "-vf",       "pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white",
      "-c:v",      "libx264",
      "-pix_fmt",  "yuv420p",
      "-movflags", "+faststart",
      "-f",        "mp4"};
  const std::vector<std::string> gif_args = {
      "-vf", "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=sierra2_4a",
      "-f", "gif"};
  for (const std::string& a : gif ? gif_args : mp4_args) args.push_back(a);
  args.push_back(tmp);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  const int messages = ::memfd_create("ffmpeg-messages", MFD_CLOEXEC);  // -1: inherit stderr
  int progress[2] = {-1, -1};
  if (::pipe2(progress, O_CLOEXEC) != 0) progress[0] = progress[1] = -1;
  const pid_t pid = ::fork();
  if (pid < 0) {
    if (messages >= 0) ::close(messages);
    for (int fd : progress)
      if (fd >= 0) ::close(fd);
    return "cannot start ffmpeg: fork failed";
  }
  if (pid == 0) {
    if (dir_fd >= 0 && ::fchdir(dir_fd) != 0) std::_Exit(127);
    if (messages >= 0) ::dup2(messages, STDERR_FILENO);
    ::dup2(progress[1] >= 0 ? progress[1] : ::open("/dev/null", O_WRONLY), STDOUT_FILENO);
    ::execv(argv[0], argv.data());
    std::_Exit(127);
  }
  forward_interrupts_to(pid);
  if (progress[1] >= 0) ::close(progress[1]);
  // "frame=N" lines until ffmpeg closes its end (it exits).
  if (progress[0] >= 0) {
    std::string pending;
    char buf[512];
    for (;;) {
      const ssize_t n = ::read(progress[0], buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      pending.append(buf, static_cast<size_t>(n));
      for (size_t eol; (eol = pending.find('\n')) != std::string::npos; pending.erase(0, eol + 1))
        if (pending.compare(0, 6, "frame=") == 0) on_frame(std::atoi(pending.c_str() + 6));
    }
    ::close(progress[0]);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      forward_interrupts_to(0);
      if (messages >= 0) ::close(messages);
      return "ffmpeg: waitpid failed";
    }
  }
  forward_interrupts_to(0);
  const bool failed = !WIFEXITED(status) || WEXITSTATUS(status) != 0;
  // ffmpeg 5.1 exits 0 after failing to write (a full disk, a file-size limit: SIGXFSZ is
  // ignored, so it gets EFBIG): what it wrote is checked before it may be the movie.
  std::uint64_t written = 0;
  const std::string incomplete = failed ? "" : check_movie_at(at, tmp, gif, frames, &written);
  if (messages >= 0) {
    if ((failed || !incomplete.empty()) && !interrupted()) {  // ffmpeg's messages to stderr
      char buf[4096];
      off_t offset = 0;
      for (ssize_t n; (n = ::pread(messages, buf, sizeof buf, offset)) > 0; offset += n)
        (void)!::write(STDERR_FILENO, buf, static_cast<size_t>(n));
    }
    ::close(messages);
  }
  if (failed) {
    ::unlinkat(at, tmp.c_str(), 0);
    if (interrupted()) return "";  // the caller reports the interruption
    return "ffmpeg could not make " + final_path + " (exit status " +
           std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "; its message is above)";
  }
  if (!incomplete.empty()) {
    const std::string cause = likely_write_failure(at, tmp, written);
    ::unlinkat(at, tmp.c_str(), 0);
    if (interrupted()) return "";  // the caller reports the interruption
    return final_path + ": write failed" + (cause.empty() ? "" : ": " + cause) +
           "; what ffmpeg wrote is no complete movie (" + incomplete + "), none was kept";
  }
  if (::renameat(at, tmp.c_str(), at, final_name.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlinkat(at, tmp.c_str(), 0);
    return final_path + ": cannot rename into place: " + reason;
  }
  *made = true;
  return "";
}

}  // namespace invfree
