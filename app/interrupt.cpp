#include "app/interrupt.h"

#include <signal.h>

#include "app/exit_codes.h"

namespace invfree {

namespace {
// Written by the handler, read between steps: a lock-free atomic of this type is the only
// thing a signal handler may portably touch.
volatile sig_atomic_t g_signal = 0;
volatile sig_atomic_t g_child = 0;

constexpr int kHandled[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void on_interrupt(int sig) {
  g_signal = sig;
  if (g_child > 0) ::kill(static_cast<pid_t>(g_child), sig);  // async-signal-safe
}
}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the first signal only sets the flag; a second one takes the default
  // action and ends the process. SA_RESTART: library calls that a signal lands in (file
  // writes, pipes to ffmpeg) are resumed rather than failing with EINTR.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigset_t unblock;
  sigemptyset(&unblock);
  for (const int sig : kHandled) {
    struct sigaction current {};
    if (sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaction(sig, &action, nullptr);
    sigaddset(&unblock, sig);
  }
  sigprocmask(SIG_UNBLOCK, &unblock, nullptr);
  signal(SIGXFSZ, SIG_IGN);
}

bool interrupted() {
  return g_signal != 0;
}

int interrupt_signal() {
  return static_cast<int>(g_signal);
}

int interrupted_exit_code() {
  return g_signal == SIGHUP ? exit_code::kHangUp : exit_code::kInterrupted;
}

void forward_interrupts_to(pid_t child) {
  g_child = static_cast<sig_atomic_t>(child);
}

}  // namespace invfree
