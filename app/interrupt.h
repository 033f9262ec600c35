// Graceful interruption of every command. Ctrl-C (SIGINT), SIGTERM or a hang-up (SIGHUP:
// the terminal or SSH session went away) only sets a flag; a command checks
// `interrupted()` between steps or frames, and Newton between its iterations (main installs
// it as solver/newton_interrupt.h's check: one long step stops too, and is not kept). So
// whatever it has written so far is complete, it writes nothing partial, and it exits
// with `interrupted_exit_code()` (129 after SIGHUP, 130 after SIGINT or SIGTERM). A second signal kills the process at once (the
// default action), for a command that is stuck; atomic writes still leave no truncated
// file under a final name, at most a stray "*.tmp<pid>".
// The handlers are installed first thing in main, so a signal during start-up (scene
// loading, output checks, the offscreen context) is handled like one during the run.
// A signal the parent set to be ignored stays ignored (`nohup invfree ...` keeps running
// after a hang-up), and one it blocked is unblocked.
// While a child process runs (ffmpeg), the signal is passed on to it, so that the child
// stops too and the command can report the interruption.
// Also ignores SIGXFSZ, so a file-size limit (ulimit -f) shows up as a write error we
// report (like a full disk) instead of silently killing the process.
#pragma once

#include <sys/types.h>

namespace invfree {

// Installs the handlers. Call once, at the start of main.
void install_interrupt_handlers();
// True once SIGINT, SIGTERM or SIGHUP arrived.
bool interrupted();
// The signal that interrupted, or 0.
int interrupt_signal();
// exit_code::kHangUp after SIGHUP, exit_code::kInterrupted otherwise.
int interrupted_exit_code();
// The child process (0: none) that an interrupting signal is passed on to.
void forward_interrupts_to(pid_t child);

}  // namespace invfree
