// How a caller controls a long sweep of runs (`invfree study`, `invfree stability`):
// the quick version (each sweep says what it leaves out), a progress line per run, and a
// stop request checked between runs (Ctrl-C), and the methods to run (`--methods`: a
// subset for a slide; empty: every method).
#pragma once

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace invfree {

struct SweepOptions {
  bool quick = false;
  std::function<void(const std::string&)> progress;  // one line per run; may be empty
  std::function<bool()> stop;                        // checked between runs; may be empty
  std::vector<std::string> methods;                  // names (methods.h); empty: all

  bool wants(const std::string& method) const {
    return methods.empty() || std::find(methods.begin(), methods.end(), method) != methods.end();
  }

  void report(const std::string& line) const {
    if (progress) progress(line);
  }
  bool stop_requested() const { return stop && stop(); }
};

}  // namespace invfree
