// See process_limits.h.
#include "app/process_limits.h"

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "app/exit_codes.h"

namespace invfree {

namespace {

// The soft limit of `resource` when it is below `below`, else 0.
rlim_t limit_of(int resource, rlim_t below = RLIM_INFINITY) {
  struct rlimit r {};
  if (::getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY || r.rlim_cur >= below)
    return 0;
  return r.rlim_cur;
}

char g_crash_line[160];
size_t g_crash_length = 0;

extern "C" void on_crash_under_limit(int) {
  (void)!::write(STDERR_FILENO, g_crash_line, g_crash_length);  // async-signal-safe
  ::_exit(exit_code::kRunFailed);
}

// SIGSEGV and SIGBUS become one line and exit 3, on a stack of their own (the crash may
// be a stack that could not grow).
void report_crashes_as_out_of_memory(const char* which, rlim_t bytes) {
  const int n = std::snprintf(g_crash_line, sizeof g_crash_line,
                              "invfree: out of memory: a library crashed, most likely on a "
                              "failed allocation under the %s limit of %lu MB; raise it\n",
                              which, static_cast<unsigned long>(bytes >> 20));
  g_crash_length = n > 0 ? std::min(static_cast<size_t>(n), sizeof g_crash_line - 1) : 0;
  static char stack[1 << 16];
  stack_t alt{};
  alt.ss_sp = stack;
  alt.ss_size = sizeof stack;
  ::sigaltstack(&alt, nullptr);
  struct sigaction action {};
  action.sa_handler = on_crash_under_limit;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_ONSTACK | SA_RESETHAND;
  ::sigaction(SIGSEGV, &action, nullptr);
  ::sigaction(SIGBUS, &action, nullptr);
}

}  // namespace

void prepare_for_resource_limits(char** argv) {
  const rlim_t address_space = limit_of(RLIMIT_AS), data = limit_of(RLIMIT_DATA);
  const char* blas_threads = std::getenv("OPENBLAS_NUM_THREADS");
  const bool blas_pinned = blas_threads != nullptr && std::strcmp(blas_threads, "1") == 0;
  // Memory limits, and a process-count limit small enough that OpenBLAS's threads could
  // fail to start (it then prints lines of its own); root is not held to the latter.
  if (!blas_pinned &&
      (address_space != 0 || data != 0 ||
       (::geteuid() != 0 && limit_of(RLIMIT_NPROC, 65536) != 0)) &&
      ::setenv("OPENBLAS_NUM_THREADS", "1", 1) == 0) {
    ::execv("/proc/self/exe", argv);
    // No /proc: go on as before (OpenBLAS's threads may then keep the process waiting at
    // exit under an address-space limit).
  }
  if (address_space != 0)
    report_crashes_as_out_of_memory("address-space (ulimit -v)", address_space);
  else if (data != 0)
    report_crashes_as_out_of_memory("data-segment (ulimit -d)", data);
}

}  // namespace invfree
