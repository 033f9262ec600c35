// The reference trajectories of the course scenes (tests/data/course/<scene>.txt, made by
// scripts/course_reference.py): one sample per line, "step x0 y0 x1 y1 ...", '#' comments.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_paths.h"

namespace invfree::test {

struct CourseSample {
  long step = 0;
  std::vector<double> x;
};

inline std::vector<CourseSample> read_course_reference(const std::string& scene) {
  std::ifstream in(std::string(source_dir()) + "/tests/data/course/" + scene + ".txt");
  std::vector<CourseSample> samples;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    CourseSample s;
    fields >> s.step;
    for (double v; fields >> v;) s.x.push_back(v);
    samples.push_back(std::move(s));
  }
  return samples;
}

}  // namespace invfree::test
