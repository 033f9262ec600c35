#include "app/interrupt.h"

#include <csignal>

namespace invfree {

namespace {
// Written by the handler, read between steps: a lock-free atomic of this type is the only
// thing a signal handler may portably touch.
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_interrupt(int sig) {
  g_signal = sig;
}
}  // namespace

void install_interrupt_handler() {
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the first signal only sets the flag; a second one takes the default
  // action and ends the process. SA_RESTART: library calls that a signal lands in (file
  // writes, pipes to ffmpeg) are resumed rather than failing with EINTR.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
}

bool interrupted() {
  return g_signal != 0;
}

int interrupt_signal() {
  return static_cast<int>(g_signal);
}

}  // namespace invfree
