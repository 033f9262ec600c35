// The reduced bases' study (app/study/reduced_study.h), its quick version: the rows (the
// full model's error 0; every reduced model's finite, positive, below a sane bound, and
// decreasing from affine to cubic and with the modal count), the CSV's columns and the
// panel's series. Speed is reported, never asserted.
#include "app/study/reduced_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace invfree {
namespace {

const ReducedStudy& quick_study() {
  static const ReducedStudy study = [] {
    SweepOptions options;
    options.quick = true;
    return run_reduced_study(options);
  }();
  return study;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, sep)) out.push_back(cell);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

TEST(ReducedStudy, TheFullModelComesFirstWithErrorZero) {
  const ReducedStudy& study = quick_study();
  ASSERT_FALSE(study.stopped);
  EXPECT_EQ(study.scene, "course-9-affine");
  EXPECT_EQ(study.steps, 200);  // the demo's length, quick too (it costs well under 1 s)
  // Quick: n_seg 10 only; full, affine, quadratic, cubic, modal 6, 12, 20.
  ASSERT_EQ(study.rows.size(), 7u);
  const ReducedStudyRow& full = study.rows[0];
  EXPECT_EQ(full.basis, "full");
  EXPECT_EQ(full.n_seg, 10);
  EXPECT_EQ(full.unknowns, 2 * 11 * 11);
  EXPECT_EQ(full.failure, "ok");
  EXPECT_EQ(full.max_error_m, 0.0);
  EXPECT_GT(full.ms_per_step, 0.0);
  EXPECT_GE(full.newton_per_step, 1.0);
  EXPECT_EQ(reduced_model_label(full), "full (242)");
}

TEST(ReducedStudy, ErrorsShrinkAsTheBasisGrows) {
  const ReducedStudy& study = quick_study();
  std::vector<double> polynomial, modal;
  std::vector<std::string> labels;
  for (const ReducedStudyRow& r : study.rows) {
    if (r.basis == "full") continue;
    EXPECT_EQ(r.failure, "ok") << reduced_model_label(r);
    EXPECT_TRUE(std::isfinite(r.max_error_m)) << reduced_model_label(r);
    EXPECT_GT(r.max_error_m, 0.0) << reduced_model_label(r);
    // The soft square (side 1) hits the ground at about 3 m/s and squashes and bounces;
    // no reduced model follows that deformation (measured: 0.1-0.46 m), but each stays
    // within half the side of the full one.
    EXPECT_LT(r.max_error_m, 0.5) << reduced_model_label(r);
    EXPECT_GT(r.ms_per_step, 0.0);
    EXPECT_LT(r.unknowns, study.rows[0].unknowns);
    labels.push_back(reduced_model_label(r));
    (r.basis == "modal" ? modal : polynomial).push_back(r.max_error_m);
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"affine (6)", "quadratic (12)", "cubic (20)",
                                              "modal 6", "modal 12", "modal 20"}));
  ASSERT_EQ(polynomial.size(), 3u);
  EXPECT_LT(polynomial[1], polynomial[0]);
  EXPECT_LT(polynomial[2], polynomial[1]);
  ASSERT_EQ(modal.size(), 3u);
  EXPECT_LT(modal[1], modal[0]);
  EXPECT_LT(modal[2], modal[1]);
}

TEST(ReducedStudy, CsvHasTheDocumentedColumns) {
  const ReducedStudy& study = quick_study();
  const std::string csv = reduced_study_csv(study);
  std::stringstream in(csv);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line,
            "basis,order_or_modes,unknowns,n_seg,ms_per_step,max_error_m,newton_per_step,failure");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line, ',');
    ASSERT_EQ(cells.size(), 8u) << line;
    const ReducedStudyRow& r = study.rows[rows++];
    EXPECT_EQ(cells[0], r.basis);
    EXPECT_EQ(std::stoi(cells[1]), r.order_or_modes);
    EXPECT_EQ(std::stoi(cells[2]), r.unknowns);
    EXPECT_EQ(std::stoi(cells[3]), 10);
    EXPECT_NEAR(std::stod(cells[5]), r.max_error_m, 1e-5 * r.max_error_m);
    EXPECT_EQ(cells[7], "ok");
  }
  EXPECT_EQ(rows, study.rows.size());
}

TEST(ReducedStudy, PanelHasOneLabelledPointPerReducedModelAndTheFullModelsLine) {
  const ReducedStudy& study = quick_study();
  const ChartSpec spec = reduced_study_panel(study);
  EXPECT_TRUE(spec.log_x && spec.log_y);
  EXPECT_FALSE(spec.notes.empty());
  ASSERT_EQ(spec.series.size(), 3u);
  const Series& full = spec.series[0];
  EXPECT_EQ(full.label, "full model (242 unknowns)");
  ASSERT_EQ(full.x.size(), 2u);
  EXPECT_EQ(full.x[0], study.rows[0].ms_per_step);
  EXPECT_EQ(full.x[1], full.x[0]);
  EXPECT_LT(full.y[0], full.y[1]);
  EXPECT_GT(full.dash, 0.0);
  EXPECT_FALSE(full.markers);
  EXPECT_EQ(spec.series[1].label, "polynomial bases");
  EXPECT_EQ(spec.series[1].point_labels,
            (std::vector<std::string>{"affine (6)", "quadratic (12)", "cubic (20)"}));
  EXPECT_EQ(spec.series[2].label, "modal bases");
  EXPECT_EQ(spec.series[2].point_labels,
            (std::vector<std::string>{"modal 6", "modal 12", "modal 20"}));
  // The line spans every point's error.
  for (std::size_t s = 1; s < 3; ++s)
    for (double y : spec.series[s].y) {
      EXPECT_LT(full.y[0], y);
      EXPECT_GT(full.y[1], y);
    }
}

}  // namespace
}  // namespace invfree
