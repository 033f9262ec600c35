#include "app/live/triangle_inspection.h"

#include "triangle_fields.h"

namespace invfree::live {

void TriangleInspection::select(const Simulation& sim, int t, long mesh_generation) {
  if (t < 0 || t >= sim.mesh.triangle_count()) return;
  selected_ = t;
  generation_ = mesh_generation;
  update(sim, mesh_generation);
}

void TriangleInspection::update(const Simulation& sim, long mesh_generation) {
  if (selected_ < 0) return;
  if (mesh_generation != generation_ || selected_ >= sim.mesh.triangle_count()) {
    release();
    return;
  }
  inspected_.triangle = selected_;
  inspected_.step = sim.step_count;
  inspected_.elastic = sim.scene.has_triangle_elasticity();
  if (!inspected_.elastic) return;
  inspected_.analysis = analyze_triangle(sim, selected_);
  // The check needs a finite Psi around F (an inverted neo-Hookean triangle has none).
  inspected_.fd = inspected_.analysis.finite
                      ? finite_difference_errors(inspected_.analysis.model, inspected_.analysis.F,
                                                 inspected_.analysis.lame)
                      : FiniteDifferenceErrors{};
}

}  // namespace invfree::live
