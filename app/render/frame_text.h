// The words and numbers a frame shows, as plain strings (no GL): the overlay lines
// (scene, model, mu, lambda, t, step, min/max det F, inverted count) and the colour bar's
// ticks. Kept apart from the drawing so that they can be tested directly.
#pragma once

#include <string>
#include <vector>

#include "material/material.h"
#include "scene/scene.h"

namespace invfree::render {

// "35.7 kPa", "143 kPa", "1.00 MPa", "850 Pa": three significant digits with an SI prefix.
std::string format_si(double value, const char* unit);
// The time with as many decimals as the time step needs (at least two): "t = 1.23 s".
std::string format_time(double t, double h);
// "neo-Hookean", "linear", "ARAP", "stable neo-Hookean".
const char* model_display_name(Model m);
// The method that steps the scene, in two short lines, so that a frame shown beside
// another says which of the lecture's switches made it: the integrator ("implicit Euler",
// "symplectic Euler", "static (load steps)") and, for Newton, its Hessian projection and
// the inversion filter ("diagonal projection, filter on").
std::vector<std::string> method_lines(const SceneDef& scene);

// A tick of the det F colour bar: its value, its position on the bar in [-1, 1] (the
// colormap's det_f_scale_position) and its label ("0.25", "1", "4").
struct ColorBarTick {
  double value = 1.0;
  double position = 0.0;
  std::string label;
};
// Powers of two from 1/range to range (every k-th, symmetric around 1, so that there are at
// most nine), always including 1, labelled with three significant digits; below 2 (an
// automatic range), 1/range, 1 and range.
std::vector<ColorBarTick> color_bar_ticks(double range);

}  // namespace invfree::render
