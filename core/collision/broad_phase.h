// Broad phase of self-contact: which boundary node-edge pairs can come within dhat of each
// other during a step, without testing all pairs (n_seg 256 has 1,024 boundary edges per
// body). A uniform grid over the boundary edges' boxes:
//  - each edge's box holds its two ends at x and at x + alpha p (the box of its path over
//    the step: the moving segment stays in the convex hull of those four points);
//  - each node's box holds its path x -> x + alpha p, inflated by `inflation` (dhat), so any
//    point of the node's path within distance dhat of any point of the edge's path lies in
//    an overlapping pair of boxes (|v|_inf <= |v|_2);
//  - edges go into every cell their box covers (counting sort: no per-cell allocation);
//    cell size = the mean edge-box extent plus the inflation, enlarged where needed to keep
//    the grid within about a dozen cells per edge (bodies far apart, one long path);
//  - each node visits the cells its box covers and keeps the edges whose boxes overlap its
//    own, except its own incident edges; a pair is reported only from the cell holding the
//    lower corner of the two boxes' intersection, so once, with no deduplication.
// Output: pairs sorted by (node, edge), the same list whatever the grid and the thread
// count (blocks of nodes query the grid concurrently, each into its own list, joined in
// node order), so that sums over it are bit-identical. Built once per Newton iteration
// over the whole line-search segment (alpha = the largest step), the list serves the
// energy, the CCD and every trial point. The grid's buffers are reused: no allocation
// once they have grown.
#pragma once

#include <array>
#include <vector>

#include "scene/boundary.h"

namespace invfree {

struct Box {
  Vec2 lo, hi;
};

// Cells [i0, i1] x [j0, j1] that a box covers.
struct CellRange {
  int i0, i1, j0, j1;
};

struct BroadPhaseGrid {
  std::vector<Box> edge_boxes;
  std::vector<CellRange> edge_cells;  // per edge: the cells its box covers
  std::vector<int> cell_start;        // cell c holds cell_edges[cell_start[c] .. cell_start[c+1])
  std::vector<int> cell_edges;
  std::vector<std::vector<PointEdgePair>> block_pairs;  // per block of nodes (candidates)
  Vec2 origin = Vec2::Zero();
  double cell_size = 1.0;
  int nx = 0, ny = 0;
};

// Room for `per_node` candidates per boundary node in the per-block lists, so that the
// search allocates nothing until some block's nodes have more.
void reserve_candidates(int node_count, int per_node, BroadPhaseGrid& grid);
// Static pairs at x (no motion). x: 2 per mesh node (entries past 2N ignored).
void point_edge_candidates(const Boundary& boundary, const VecX& x, double inflation,
                           BroadPhaseGrid& grid, std::vector<PointEdgePair>& out);
// Pairs over the path x -> x + alpha p.
void swept_point_edge_candidates(const Boundary& boundary, const VecX& x, const VecX& p,
                                 double alpha, double inflation, BroadPhaseGrid& grid,
                                 std::vector<PointEdgePair>& out);
// Pairs of boundary edges (e < f) whose boxes at x overlap, adjacent ones included: the
// candidates of the intersection check.
void edge_edge_candidates(const Boundary& boundary, const VecX& x, BroadPhaseGrid& grid,
                          std::vector<std::array<int, 2>>& out);

}  // namespace invfree
