// The live inspector's state, independent of any window: which triangle the user clicked
// (or --select-triangle chose), and that triangle's analysis recomputed from the current
// state every frame (the lecture's quantities, core/triangle_fields.h, plus the finite-
// difference check of P and dP/dF: the same numbers `invfree inspect` prints). A mesh
// rebuild (a new scene, n_seg, a switch to or from the springs) releases the selection,
// since its index would name another triangle, or none.
#pragma once

#include <optional>

#include "material/stress_analysis.h"
#include "simulation.h"

namespace invfree::live {

// What the inspector panel shows for the selected triangle, as of `step`.
struct Inspected {
  int triangle = -1;
  long step = 0;
  // False for a mass-spring scene: its triangles carry no elasticity (the panel says n/a
  // and analysis/fd are left as they are).
  bool elastic = true;
  StressAnalysis analysis;
  FiniteDifferenceErrors fd;
};

class TriangleInspection {
 public:
  // Selects triangle t of `sim`'s mesh (ignored when out of range).
  void select(const Simulation& sim, int t, long mesh_generation);
  void release() { selected_ = -1; }
  int selected() const { return selected_; }
  // Recomputes the analysis from `sim` (once per frame); releases the selection when the
  // mesh was rebuilt since it was made (`mesh_generation` differs) or the index left the
  // mesh.
  void update(const Simulation& sim, long mesh_generation);
  // The last update's values; null with nothing selected.
  const Inspected* inspected() const { return selected_ >= 0 ? &inspected_ : nullptr; }

 private:
  int selected_ = -1;
  long generation_ = 0;
  Inspected inspected_;
};

}  // namespace invfree::live
