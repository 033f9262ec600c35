// What the program does first, for a process started under resource limits (ulimit -v,
// -d, -u).
// - OpenBLAS, loaded with CHOLMOD, starts one worker thread per core before main runs,
//   and each worker at once maps a 128 MiB buffer; under an address-space limit the
//   mapping fails, the worker retries it forever, and OpenBLAS's exit handler waits for
//   that worker: the command would print its output and never exit. invfree runs BLAS on
//   one thread anyway (CHOLMOD's determinism, linalg/cholmod_backend.cpp), but OpenBLAS
//   reads its thread count only from the environment, when it is loaded. So a process
//   started with such a limit and without OPENBLAS_NUM_THREADS=1 sets it and executes
//   itself again (/proc/self/exe, the same arguments) before anything else has happened;
//   the workers are never made. Without a limit nothing happens (no second start).
// - Under a memory limit, libraries that do not check their allocations (OSMesa's
//   shader compiler, llvmpipe) crash with SIGSEGV instead of reporting it. Then the
//   crash is reported as what it almost surely is: one line, "out of memory" with the
//   limit, exit 3 (exit_code::kRunFailed), instead of a bare "Segmentation fault".
//   Without a memory limit a crash stays a crash (core dump, sanitizers' reports).
#pragma once

namespace invfree {

// Call first in main, before the signal handlers are installed (an exec keeps a signal
// blocked or pending, and one ignored stays ignored). Returns when no restart is needed
// or the restart failed (then the run goes on as it would have).
void prepare_for_resource_limits(char** argv);

}  // namespace invfree
