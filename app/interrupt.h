// Graceful interruption of long commands (simulate, render, ...). Ctrl-C (SIGINT) or
// SIGTERM only sets a flag; a command checks `interrupted()` between steps or frames, so
// whatever it has written so far is complete, it writes nothing partial, and it exits
// with exit_code::kInterrupted. A second Ctrl-C kills the process at once (the default
// action), for a command that is stuck; atomic writes still leave no truncated file under
// a final name, at most a stray "*.tmp<pid>".
// Also ignores SIGXFSZ, so a file-size limit (ulimit -f) shows up as a write error we
// report (like a full disk) instead of silently killing the process.
#pragma once

namespace invfree {

// Installs the handlers and clears the flag. Call once at the start of a command.
void install_interrupt_handler();
// True once SIGINT or SIGTERM arrived after install_interrupt_handler().
bool interrupted();
// The signal that interrupted (SIGINT or SIGTERM), or 0.
int interrupt_signal();

}  // namespace invfree
