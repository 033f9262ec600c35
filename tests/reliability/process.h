// Runs the invfree executable from tests: synchronously (exit code, stdout, stderr) or in
// the background (for signals). Arguments are passed as a vector, never through a shell,
// so paths need no quoting; `shell_prefix` (e.g. "ulimit -f 4;") runs it under bash.
// SpawnOptions: stdout to a given file (a device node, a file the command also names),
// a process group of its own (to imitate a terminal's Ctrl-C, which reaches the command
// and its children), signals blocked at the start (to deliver one before main runs).
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/run_command.h"  // slurp, one_line
#include "tests/test_paths.h"

extern char** environ;

namespace invfree::test {

struct SpawnOptions {
  std::string stdout_path;         // "": captured into a temporary file; else appended to
  bool own_process_group = false;  // the child leads a new group: kill(-pid, sig) signals it all
  std::vector<int> blocked;        // signals blocked in the child when it starts
};

inline SpawnOptions stdout_to(const std::string& path) {
  SpawnOptions o;
  o.stdout_path = path;
  return o;
}
inline SpawnOptions with_blocked(int sig) {
  SpawnOptions o;
  o.blocked = {sig};
  return o;
}
inline SpawnOptions in_own_process_group() {
  SpawnOptions o;
  o.own_process_group = true;
  return o;
}

struct ProcessResult {
  int code = -1;  // exit code, or -signal when killed by a signal
  std::string out, err;
};

inline int decode_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return -1000;
}

class Process {
 public:
  // Starts `args` (args[0] is the program) with extra "NAME=value" environment entries.
  Process(const std::vector<std::string>& args, const std::vector<std::string>& env_extra = {},
          const std::string& shell_prefix = "", const SpawnOptions& options = {}) {
    static int counter = 0;
    const std::string tag = ::testing::TempDir() + "/proc_" + std::to_string(::getpid()) + "_" +
                            std::to_string(counter++);
    out_path_ = options.stdout_path.empty() ? tag + ".out" : options.stdout_path;
    stdout_captured_ = options.stdout_path.empty();
    err_path_ = tag + ".err";
    std::vector<std::string> argv_s = args;
    if (!shell_prefix.empty()) {  // bash -c 'PREFIX exec "$0" "$@"' prog args...
      argv_s.insert(argv_s.begin(), {"/bin/bash", "-c", shell_prefix + " exec \"$0\" \"$@\""});
    }
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_s;
    for (char** e = environ; *e; ++e) env_s.emplace_back(*e);
    for (const auto& e : env_extra) env_s.push_back(e);
    std::vector<char*> envp;
    for (auto& e : env_s) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(
        &actions, 1, out_path_.c_str(),
        O_WRONLY | O_CREAT | (options.stdout_path.empty() ? O_TRUNC : O_APPEND), 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    // The child must start with default signal dispositions whatever the test runner set.
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGHUP);
    sigaddset(&defaults, SIGXFSZ);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    sigset_t mask;
    sigemptyset(&mask);
    for (const int sig : options.blocked) sigaddset(&mask, sig);
    posix_spawnattr_setsigmask(&attr, &mask);
    short flags = POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK;
    if (options.own_process_group) {
      posix_spawnattr_setpgroup(&attr, 0);
      flags |= POSIX_SPAWN_SETPGROUP;
    }
    posix_spawnattr_setflags(&attr, flags);
    if (posix_spawn(&pid_, argv[0], &actions, &attr, argv.data(), envp.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
  }
  ~Process() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }
  pid_t pid() const { return pid_; }
  // Waits at most `seconds` (a guard against a hang, not a timing check): false when the
  // process has not exited by then (the destructor kills it).
  bool exits_within(int seconds) {
    if (pid_ <= 0 || waited_) return true;
    for (int i = 0; i < seconds * 100; ++i) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        waited_ = true;
        status_ = status;
        return true;
      }
      ::usleep(10000);
    }
    return false;
  }
  ProcessResult wait() {
    ProcessResult r;
    if (pid_ <= 0) return r;
    int status = status_;
    if (!waited_)
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    waited_ = true;
    status_ = status;
    r.code = decode_status(status);
    r.out = stdout_captured_ ? slurp(out_path_) : "";
    r.err = slurp(err_path_);
    return r;
  }

 private:
  pid_t pid_ = -1;
  bool waited_ = false;
  int status_ = 0;
  std::string out_path_, err_path_;
  bool stdout_captured_ = true;
};

inline ProcessResult run_invfree(const std::vector<std::string>& args,
                                 const std::vector<std::string>& env = {},
                                 const std::string& shell_prefix = "",
                                 const SpawnOptions& options = {}) {
  std::vector<std::string> full = {::invfree::test::exe_path()};
  full.insert(full.end(), args.begin(), args.end());
  return Process(full, env, shell_prefix, options).wait();
}

}  // namespace invfree::test
