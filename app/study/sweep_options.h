// How a caller controls a long sweep of runs (`invfree study`, `invfree stability`):
// the quick version (each sweep says what it leaves out), a progress line per run, and a
// stop request checked between runs (Ctrl-C), the methods to run (`--methods`: a subset
// for a slide; empty: every method) and, for `stability`, its scenes (`--scenes`).
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
  std::vector<std::string> scenes;                   // stability's columns; empty: all

  bool wants(const std::string& method) const {
    return methods.empty() || std::find(methods.begin(), methods.end(), method) != methods.end();
  }

  bool wants_scene(const std::string& scene) const {
    return scenes.empty() || std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
  }

  void report(const std::string& line) const {
    if (progress) progress(line);
  }
  bool stop_requested() const { return stop && stop(); }
};

}  // namespace invfree
