// See movie.h.
#include "app/movie.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "app/interrupt.h"

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

std::string make_movie(const std::string& ffmpeg, const std::string& dir, int frames, double fps,
                       bool gif, const std::function<void(int)>& on_frame, bool* made,
                       const std::string& movie_path) {
  *made = false;
  const std::string ext = gif ? "gif" : "mp4";
  const std::string final_path = movie_path.empty() ? dir + "/movie." + ext : movie_path;
  // Beside the final path (the rename stays within its directory): "<stem>.tmp<pid>.<ext>".
  const size_t dot = final_path.rfind('.'), slash = final_path.rfind('/');
  const std::string stem = dot != std::string::npos && (slash == std::string::npos || dot > slash)
                               ? final_path.substr(0, dot)
                               : final_path;
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
                                   dir + "/frame_%06d.png",
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
  if (messages >= 0) {
    if (failed && !interrupted()) {  // copy ffmpeg's messages to our stderr
      char buf[4096];
      off_t at = 0;
      for (ssize_t n; (n = ::pread(messages, buf, sizeof buf, at)) > 0; at += n)
        (void)!::write(STDERR_FILENO, buf, static_cast<size_t>(n));
    }
    ::close(messages);
  }
  std::error_code ec;
  if (failed) {
    std::filesystem::remove(tmp, ec);
    if (interrupted()) return "";  // the caller reports the interruption
    return "ffmpeg could not make " + final_path + " (exit status " +
           std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "; its message is above)";
  }
  std::filesystem::rename(tmp, final_path, ec);
  if (ec) return final_path + ": cannot rename into place: " + ec.message();
  *made = true;
  return "";
}

}  // namespace invfree
