// The lowest-index triangle whose det F fails a test (the step's inversion and finiteness
// checks, simulation.cpp), over fixed blocks of triangles on the pool: each block finds
// its own lowest failing index, and the first block that has one answers. The answer is
// the serial scan's for any thread count; at n_seg 256 one pass is ~0.5 ms on one thread.
#pragma once

#include "potential/elasticity.h"
#include "potential/work_blocks.h"
#include "scene/mesh.h"

namespace invfree {

// `ok(det F)` for every triangle of `mesh` at positions x (2 per node); the first t whose
// det F fails it, or -1.
template <class Ok>
int first_failing_triangle(const Mesh& mesh, const double* x, Ok&& ok) {
  const int nt = mesh.triangle_count();
  const BlockSplit tri = split_blocks(nt, kTriangleBlock, kMaxBlocks);
  int first[kMaxBlocks];
  run_blocks(tri.blocks, [&](int b) {
    first[b] = -1;
    for (int t = tri.begin(b), end = tri.end(b, nt); t < end; ++t)
      if (!ok(triangle_deformation_gradient(mesh, x, t).determinant())) {
        first[b] = t;
        break;
      }
  });
  for (int b = 0; b < tri.blocks; ++b)
    if (first[b] >= 0) return first[b];
  return -1;
}

}  // namespace invfree
