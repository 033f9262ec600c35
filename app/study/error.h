// The study's accuracy measure and its convergence fit.
// rms_position_error: sqrt(mean over sample times and nodes of |x - x_ref|^2) / side,
// where node i of the run is compared with node map[i] of the reference (identity when
// the map is empty): a run on a coarser mesh is compared at the nodes it shares with a
// finer reference. NaN when the runs do not have the same number of samples.
// loglog_slope: least-squares slope of log y against log x (app/plot/loglog_fit.h: points
// with x, y <= 0 or non-finite are skipped; NaN with fewer than two points).
#pragma once

#include <vector>

#include "types.h"

namespace invfree {

double rms_position_error(const std::vector<VecX>& run, const std::vector<VecX>& reference,
                          double side, const std::vector<int>& node_map = {});

// For square meshes numbered i*(n+1)+j: node (i, j) of the n_coarse mesh is node
// (i k, j k) of the n_fine mesh, k = n_fine / n_coarse. Empty when n_fine is not a multiple.
std::vector<int> nested_node_map(int n_coarse, int n_fine);

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace invfree
