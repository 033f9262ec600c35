// The step time as the live panel and the web page show it (issue 32 item 12): small scenes
// read "0.00 ms/step" with two decimals of a millisecond, and in a browser one step's time
// is a tick of its clock (performance.now() is coarsened to 0.1 ms on a page without
// cross-origin isolation), so one small step reads 0 or 100 μs. Shown instead: the mean
// over the steps of the panel's ms/step plot, in μs below a millisecond, three significant
// digits.
#pragma once

#include <string>
#include <vector>

namespace invfree::live {

// "51.2 μs/step", "1.73 ms/step", "412 ms/step"; "- ms/step" for a negative or NaN time.
std::string step_time_text(double ms);

// The figure shown: the mean of `recent_ms` (the plot's steps), or `last_ms` when empty.
double shown_step_ms(const std::vector<float>& recent_ms, double last_ms);

}  // namespace invfree::live
