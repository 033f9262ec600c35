#include "collision/broad_phase.h"

#include <algorithm>
#include <cmath>

#include "potential/work_blocks.h"

namespace invfree {

namespace {

constexpr int kMaxCellsPerEdge = 4;
// Boundary nodes per block of the candidate search: ~40 us of queries at n_seg 256.
constexpr int kQueryBlock = 128;

Box point_box(const Vec2& v) {
  return {v, v};
}

void grow(Box& box, const Vec2& v) {
  box.lo = box.lo.cwiseMin(v);
  box.hi = box.hi.cwiseMax(v);
}

bool overlap(const Box& a, const Box& b) {
  return a.lo.x() <= b.hi.x() && b.lo.x() <= a.hi.x() && a.lo.y() <= b.hi.y() &&
         b.lo.y() <= a.hi.y();
}

// The box of node i's path x -> x + alpha p (p null: the point itself).
Box path_box(const VecX& x, const VecX* p, double alpha, int i) {
  const Vec2 v = x.segment<2>(2 * i);
  Box box = point_box(v);
  if (p) grow(box, v + alpha * p->segment<2>(2 * i));
  return box;
}

// Cell coordinate of v along one axis, clamped to [0, n - 1] (NaN goes to 0; monotone in v,
// so a box's cell range contains the cell of every point inside it).
int cell_coordinate(double v, double origin, double size, int n) {
  const double c = std::floor((v - origin) / size);
  if (!(c >= 0.0)) return 0;
  return c >= n - 1 ? n - 1 : static_cast<int>(c);
}

CellRange cell_range(const BroadPhaseGrid& g, const Box& box) {
  return {cell_coordinate(box.lo.x(), g.origin.x(), g.cell_size, g.nx),
          cell_coordinate(box.hi.x(), g.origin.x(), g.cell_size, g.nx),
          cell_coordinate(box.lo.y(), g.origin.y(), g.cell_size, g.ny),
          cell_coordinate(box.hi.y(), g.origin.y(), g.cell_size, g.ny)};
}

void build_grid(const Boundary& boundary, const VecX& x, const VecX* p, double alpha,
                double inflation, BroadPhaseGrid& g) {
  const int ne = boundary.edge_count();
  g.edge_boxes.resize(ne);
  Box bounds = {Vec2::Constant(INFINITY), Vec2::Constant(-INFINITY)};
  double extent = 0.0;
  for (int k = 0; k < ne; ++k) {
    Box box = path_box(x, p, alpha, boundary.edges[k][0]);
    const Box other = path_box(x, p, alpha, boundary.edges[k][1]);
    grow(box, other.lo);
    grow(box, other.hi);
    g.edge_boxes[k] = box;
    grow(bounds, box.lo);
    grow(bounds, box.hi);
    extent += (box.hi - box.lo).maxCoeff();
  }
  // Cell size: the mean edge-box extent plus the inflation, at least what keeps the grid
  // within kMaxCellsPerEdge cells per edge along the area and along the longer side (so
  // nx * ny <= 3 * budget + 1). Non-finite positions get one cell (no pair is found in
  // it: comparisons with NaN are false).
  const double budget = kMaxCellsPerEdge * (ne + 1.0);
  const Vec2 span = ne > 0 ? Vec2(bounds.hi - bounds.lo) : Vec2::Zero();
  const double size = std::max({(ne > 0 ? extent / ne : 0.0) + inflation,
                                std::sqrt(span.x() * span.y() / budget), span.maxCoeff() / budget});
  if (span.allFinite() && size > 0.0 && std::isfinite(size)) {
    g.cell_size = size;
    g.origin = bounds.lo;
    g.nx = static_cast<int>(std::floor(span.x() / size)) + 1;
    g.ny = static_cast<int>(std::floor(span.y() / size)) + 1;
  } else {
    g.cell_size = 1.0;
    g.origin = Vec2::Zero();
    g.nx = g.ny = 1;
  }

  const int cells = g.nx * g.ny;
  g.cell_start.assign(cells + 1, 0);
  g.edge_cells.resize(ne);
  for (int k = 0; k < ne; ++k) {
    const CellRange r = g.edge_cells[k] = cell_range(g, g.edge_boxes[k]);
    for (int j = r.j0; j <= r.j1; ++j)
      for (int i = r.i0; i <= r.i1; ++i) ++g.cell_start[j * g.nx + i + 1];
  }
  for (int c = 0; c < cells; ++c) g.cell_start[c + 1] += g.cell_start[c];
  g.cell_edges.resize(g.cell_start[cells]);
  // Fill each cell in ascending edge order, using cell_start as the running cursor and
  // shifting it back afterwards.
  for (int k = 0; k < ne; ++k) {
    const CellRange& r = g.edge_cells[k];
    for (int j = r.j0; j <= r.j1; ++j)
      for (int i = r.i0; i <= r.i1; ++i) g.cell_edges[g.cell_start[j * g.nx + i]++] = k;
  }
  for (int c = cells; c > 0; --c) g.cell_start[c] = g.cell_start[c - 1];
  g.cell_start[0] = 0;
}

// Calls visit(edge) once for every edge whose box overlaps `box`: from the cell holding the
// lower corner of the two boxes' intersection. That corner is the larger of the two lower
// corners, and cell_coordinate is monotone, so its cell is the larger of their cells: no
// coordinate is computed per candidate.
template <class Visit>
void query(const BroadPhaseGrid& g, const Box& box, Visit&& visit) {
  if (g.nx == 0) return;
  const CellRange r = cell_range(g, box);
  for (int j = r.j0; j <= r.j1; ++j)
    for (int i = r.i0; i <= r.i1; ++i) {
      const int c = j * g.nx + i;
      for (int s = g.cell_start[c]; s < g.cell_start[c + 1]; ++s) {
        const int e = g.cell_edges[s];
        const CellRange& er = g.edge_cells[e];
        if (i == std::max(r.i0, er.i0) && j == std::max(r.j0, er.j0) &&
            overlap(box, g.edge_boxes[e]))
          visit(e);
      }
    }
}

// One node's pairs, sorted by edge, appended to `out`.
void node_candidates(const Boundary& boundary, const VecX& x, const VecX* p, double alpha,
                     double inflation, const BroadPhaseGrid& g, int n,
                     std::vector<PointEdgePair>& out) {
  const int node = boundary.nodes[n];
  Box box = path_box(x, p, alpha, node);
  box.lo.array() -= inflation;
  box.hi.array() += inflation;
  const size_t first = out.size();
  query(g, box, [&](int e) {
    const auto& edge = boundary.edges[e];
    if (edge[0] != node && edge[1] != node) out.push_back({n, e});
  });
  std::sort(out.begin() + first, out.end());
}

void candidates(const Boundary& boundary, const VecX& x, const VecX* p, double alpha,
                double inflation, BroadPhaseGrid& g, std::vector<PointEdgePair>& out) {
  build_grid(boundary, x, p, alpha, inflation, g);
  out.clear();
  const int nodes = boundary.node_count();
  const BlockSplit split = split_blocks(nodes, kQueryBlock, kMaxBlocks);
  if (split.blocks < 2) {
    for (int n = 0; n < nodes; ++n) node_candidates(boundary, x, p, alpha, inflation, g, n, out);
    return;
  }
  // Each block of nodes fills its own list; the lists joined in block order are the serial
  // loop's list, entry for entry, on any number of threads.
  if (g.block_pairs.size() < static_cast<size_t>(split.blocks)) g.block_pairs.resize(split.blocks);
  run_blocks(split.blocks, [&](int b) {
    // The list's buffer is moved to this thread's stack while it grows: the neighbouring
    // blocks' vector headers share cache lines, and every push_back writes its header.
    std::vector<PointEdgePair> mine;
    mine.swap(g.block_pairs[b]);
    mine.clear();
    for (int n = split.begin(b); n < split.end(b, nodes); ++n)
      node_candidates(boundary, x, p, alpha, inflation, g, n, mine);
    mine.swap(g.block_pairs[b]);
  });
  for (int b = 0; b < split.blocks; ++b)
    out.insert(out.end(), g.block_pairs[b].begin(), g.block_pairs[b].end());
}

}  // namespace

void reserve_candidates(int node_count, int per_node, BroadPhaseGrid& grid) {
  const BlockSplit split = split_blocks(node_count, kQueryBlock, kMaxBlocks);
  if (split.blocks < 2) return;
  grid.block_pairs.resize(split.blocks);
  for (int b = 0; b < split.blocks; ++b)
    grid.block_pairs[b].reserve(static_cast<size_t>(per_node) *
                                (split.end(b, node_count) - split.begin(b)));
}

void point_edge_candidates(const Boundary& boundary, const VecX& x, double inflation,
                           BroadPhaseGrid& grid, std::vector<PointEdgePair>& out) {
  candidates(boundary, x, nullptr, 0.0, inflation, grid, out);
}

void swept_point_edge_candidates(const Boundary& boundary, const VecX& x, const VecX& p,
                                 double alpha, double inflation, BroadPhaseGrid& grid,
                                 std::vector<PointEdgePair>& out) {
  candidates(boundary, x, &p, alpha, inflation, grid, out);
}

void edge_edge_candidates(const Boundary& boundary, const VecX& x, BroadPhaseGrid& grid,
                          std::vector<std::array<int, 2>>& out) {
  build_grid(boundary, x, nullptr, 0.0, 0.0, grid);
  out.clear();
  for (int f = 0; f < boundary.edge_count(); ++f) {
    const size_t first = out.size();
    query(grid, grid.edge_boxes[f], [&](int e) {
      if (e < f) out.push_back({e, f});
    });
    std::sort(out.begin() + first, out.end());
  }
}

}  // namespace invfree
