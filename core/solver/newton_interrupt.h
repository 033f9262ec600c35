// A check Newton makes between its iterations, so that a program can stop a step that
// runs long (a huge max_newton with a tiny tol) as soon as it is asked to, not only between
// steps. The program installs it once (the invfree command line: its SIGINT/SIGTERM/SIGHUP
// flag, app/interrupt.h); the default is none. When it returns true, the step ends at once
// with StepStatus::NewtonFailed and is not accepted (the simulation keeps the state of the
// last step); the caller, which knows why, reports the interruption instead of a failure.
#pragma once

namespace invfree {

using NewtonInterruptCheck = bool (*)();

// Installs `check` (nullptr: none). Called before steps run, not while one does.
void set_newton_interrupt_check(NewtonInterruptCheck check);

}  // namespace invfree
