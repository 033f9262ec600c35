// The stability sweep as one slide (`invfree stability --slides`: stability-slide.png):
// a 16:9 grid, one row per method that ran (`--methods` picks them), one column per stress
// scene, large type. A cell is coloured by its class: an ok run by the smallest det F it
// reached (the det F scale, its value written in it: how close it came to inverting, so no
// two ok cells need look alike), a failure red with its verdict, an inversion its model
// allows in a neutral blue, n/a grey. The title is the takeaway, computed from the cells:
// the lecture's record, and the method that failed most.
#pragma once

#include <memory>
#include <string>

#include "app/plot/canvas.h"
#include "app/study/stability.h"

namespace invfree {

// What a summary cell says: "0.31" (an ok run's smallest det F), "penetrated", "inverted
// (allowed)", "n/a".
std::string summary_cell_text(const StabilityCell& cell);

std::string stability_takeaway(const StabilityResult& result);

std::unique_ptr<Canvas> stability_summary(const StabilityResult& result, ChartFormat format);

}  // namespace invfree
