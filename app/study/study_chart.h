// The study's pictures, drawn with app/plot:
//   study_panels:  (A) error against wall time per simulated second, one curve per method
//                  over its h sweep, and one Pareto front per material model (each model
//                  is measured against its own reference, so errors compare only within
//                  a model), its points labelled with h;
//                  (B) error against h, with the lecture method's fitted slope (implicit
//                  Euler: first order) printed in the title and a slope-1 guide.
//   sweeps_panels: (C) the Newton tolerance sweep (points labelled with tol), (D) the mesh
//                  resolution sweep against n_seg (the title says when its y range is
//                  narrow).
// chart_canvas (app/plot/chart.h) stacks a pair into one drawing.
#pragma once

#include <string>
#include <vector>

#include "app/plot/chart.h"
#include "app/study/study.h"

namespace invfree {

Rgb method_color(const std::string& method);

// Indices of the points no other point beats in both x and y (smaller is better), by x.
std::vector<size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y);

std::vector<ChartSpec> study_panels(const StudyResult& result);
std::vector<ChartSpec> sweeps_panels(const StudyResult& result);

}  // namespace invfree
