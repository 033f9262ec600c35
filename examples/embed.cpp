// Embedding invfree: build the built-in `compress` scene, step it 100 times and print the
// lowest det F over every triangle and step. Output: "steps 100 min_det_F <value>".
#include <algorithm>
#include <cstdio>
#include <limits>

#include "invfree.h"
#include "scene_io/builtin_scenes.h"

int main() {
  const invfree::SceneLoad scene = invfree::load_builtin_scene("compress");
  if (!scene.scene) {
    std::fprintf(stderr, "%s\n", scene.error.c_str());
    return 1;
  }
  invfree::Simulation sim = invfree::make_simulation(*scene.scene);
  double min_det_f = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 100; ++k) {
    invfree::StepReport report = invfree::step(sim);
    if (report.status != invfree::StepStatus::Ok) {
      std::fprintf(stderr, "step %d failed: %s\n", k + 1, report.message.c_str());
      return 1;
    }
    for (double det_f : invfree::triangle_det_f(sim)) min_det_f = std::min(min_det_f, det_f);
  }
  std::printf("steps %ld min_det_F %.6f\n", sim.step_count, min_det_f);
}
