// The study's pictures, drawn with app/plot:
//   study_chart:  (A) error against wall time per simulated second, one curve per method
//                 over its h sweep, the Pareto front of all those points in black;
//                 (B) error against h, with the lecture method's fitted slope (implicit
//                 Euler: first order) printed in the title and a slope-1 guide.
//   sweeps_chart: (C) the Newton tolerance sweep, (D) the mesh resolution sweep.
// Each returns one image with the two panels stacked vertically.
#pragma once

#include <string>
#include <vector>

#include "app/plot/chart.h"
#include "app/study/study.h"

namespace invfree {

Rgb method_color(const std::string& method);

// Indices of the points no other point beats in both x and y (smaller is better), by x.
std::vector<size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y);

Image stack_vertical(const std::vector<Image>& panels);

Image study_chart(const StudyResult& result);
Image sweeps_chart(const StudyResult& result);

}  // namespace invfree
