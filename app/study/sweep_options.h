// How a caller controls a long sweep of runs (`invfree study`, `invfree stability`):
// the quick version (each sweep says what it leaves out), a progress line per run, and a
// stop request checked between runs (Ctrl-C).
#pragma once

#include <functional>
#include <string>

namespace invfree {

struct SweepOptions {
  bool quick = false;
  std::function<void(const std::string&)> progress;  // one line per run; may be empty
  std::function<bool()> stop;                        // checked between runs; may be empty

  void report(const std::string& line) const {
    if (progress) progress(line);
  }
  bool stop_requested() const { return stop && stop(); }
};

}  // namespace invfree
