// The study's charts as slides (`invfree study --slides`): one 16:9 chart per file
// (1920 x 1080, no notes, type large enough for the back row), the methods that ran
// (`--methods` picks them) named by their short names, and a title that is the chart's
// one-line takeaway, computed from the data:
//   speed:       error against wall time per simulated second over the h sweep; the title
//                says which method of the best-populated model is fastest at an accuracy
//                all of them reach, and which methods failed at every h
//   convergence: error against h with the check without contact and a slope-1 guide; the
//                title gives implicit Euler's order without and with contact
// A study whose errors do not fall with h says so in the titles instead of ranking.
#pragma once

#include <string>
#include <vector>

#include "app/plot/chart.h"
#include "app/study/study.h"

namespace invfree {

struct Slide {
  std::string name;  // file stem: "study-slide-speed"
  ChartSpec chart;
};

constexpr int kSlideWidth = 1920, kSlideHeight = 1080;
constexpr double kSlideTypeScale = 1.6;

std::string speed_takeaway(const StudyResult& result);
std::string convergence_takeaway(const StudyResult& result);

std::vector<Slide> study_slides(const StudyResult& result);

}  // namespace invfree
