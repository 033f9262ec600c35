// Process exit codes of every invfree command (documented in `invfree --help` and
// docs/outputs.md).
#pragma once

namespace invfree::exit_code {
constexpr int kOk = 0;
constexpr int kBadInput = 2;       // invalid command line, scene file, --set value or output
constexpr int kRunFailed = 3;      // a step failed: Newton cap, non-finite values, invariant broken
constexpr int kOutputFailed = 4;   // an output file or directory could not be written
constexpr int kHangUp = 129;       // SIGHUP: complete outputs are kept, partial ones removed
constexpr int kInterrupted = 130;  // Ctrl-C or SIGTERM: the same
}  // namespace invfree::exit_code
