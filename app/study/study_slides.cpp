#include "app/study/study_slides.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "app/format_number.h"
#include "app/study/methods.h"
#include "app/study/study_chart.h"

namespace invfree {

namespace {

// The ok points (error > 0) of `method` in the h sweep.
std::vector<const StudyRow*> ok_points(const StudyResult& r, const std::string& method) {
  std::vector<const StudyRow*> rows;
  for (const StudyRow& row : r.rows)
    if (row.method == method && in_h_sweep(r, row) && std::isfinite(row.error) && row.error > 0.0 &&
        std::isfinite(row.wall_s))
      rows.push_back(&row);
  return rows;
}

bool ran_in_h_sweep(const StudyResult& r, const std::string& method) {
  return std::any_of(r.rows.begin(), r.rows.end(), [&](const StudyRow& row) {
    return row.method == method && in_h_sweep(r, row) && row.failure != "n/a";
  });
}

std::string percent(double error) {
  return format_number(100.0 * error, error < 0.01 ? "%.1g" : "%.2g") + "%";
}

std::string ratio(double x) {
  return format_number(x, x < 10.0 ? "%.1f" : "%.0f") + "\u00d7";
}

// "a", "a and b", "a, b and c".
std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return s;
}

// "; symplectic-euler fails at every h", or "".
std::string failed_everywhere(const StudyResult& r) {
  std::vector<std::string> failed;
  for (const std::string& m : study_methods_run(r))
    if (ran_in_h_sweep(r, m) && ok_points(r, m).empty()) failed.push_back(m);
  if (failed.empty()) return "";
  return "; " + join_names(failed) + (failed.size() == 1 ? " fails" : " fail") + " at every h";
}

}  // namespace

std::string speed_takeaway(const StudyResult& r) {
  if (every_run_failed(r)) return "Every run of " + r.scene.name + " failed: nothing to compare";
  // Errors compare only within a model: rank the model with the most methods that have an
  // error (the lecture's first on a tie, being first in the table).
  std::vector<std::string> models;
  std::map<std::string, std::vector<std::string>> members;
  for (const std::string& m : study_methods_run(r)) {
    if (ok_points(r, m).empty()) continue;
    const std::string model = method_model(*find_method(m));
    if (!members.count(model)) models.push_back(model);
    members[model].push_back(m);
  }
  const auto best = std::max_element(models.begin(), models.end(), [&](auto& a, auto& b) {
    return members[a].size() < members[b].size();
  });
  if (best == models.end()) return "No run of " + r.scene.name + " has an error to compare";
  const std::string& model = *best;
  if (const ModelConvergence* c = model_convergence(r, model); c && c->judged && !c->converges)
    return "On " + r.scene.name + " the " + model + " errors do not converge with h (" +
           format_number(100.0 * c->error_lo, "%.2g") + "-" + percent(c->error_hi) +
           " of the side, slope " + format_number(c->slope, "%.2f") + "): they rank no method" +
           failed_everywhere(r);
  const std::vector<std::string>& ms = members[model];
  // An accuracy every one of them reaches: the largest of their smallest errors.
  double target = 0.0;
  for (const std::string& m : ms) {
    double lo = INFINITY;
    for (const StudyRow* row : ok_points(r, m)) lo = std::min(lo, row->error);
    target = std::max(target, lo);
  }
  std::vector<std::pair<double, std::string>> cost;  // wall time at error <= target
  for (const std::string& m : ms) {
    double w = INFINITY;
    for (const StudyRow* row : ok_points(r, m))
      if (row->error <= target) w = std::min(w, row->wall_s);
    cost.emplace_back(w, m);
  }
  std::sort(cost.begin(), cost.end());
  if (cost.size() == 1)
    return cost[0].second + " reaches " + percent(target) + " error at " +
           format_number(cost[0].first, "%.2g") + " s per simulated s" + failed_everywhere(r);
  return "At " + percent(target) + " error " + cost[0].second + " is fastest, " +
         cost.back().second + " " + ratio(cost.back().first / cost[0].first) + " slower" +
         failed_everywhere(r);
}

std::string convergence_takeaway(const StudyResult& r) {
  std::string s;
  if (std::isfinite(r.smooth_slope)) {
    s = "Implicit Euler without contact: " +
        std::string(std::abs(r.smooth_slope - 1.0) < 0.15 ? "first order" : "order") + " (slope " +
        format_number(r.smooth_slope, "%.2f") + ")";
  }
  const ModelConvergence* c = model_convergence(r, "neo-hookean");
  if (std::isfinite(r.lecture_slope)) {
    const bool flat = c && c->judged && !c->converges;
    s += std::string(s.empty() ? "Implicit Euler with contact: " : "; with contact: ") +
         (flat ? "the error does not fall with h (slope " : "slope ") +
         format_number(r.lecture_slope, "%.2f") + (flat ? ")" : "");
  }
  if (s.empty()) s = "Error against h on " + r.scene.name;
  return s + failed_everywhere(r);
}

std::vector<Slide> study_slides(const StudyResult& r) {
  auto base = [&](const std::string& title, const std::string& x_label) {
    ChartSpec c;
    c.title = title;
    c.x_label = x_label;
    c.y_label = "error / side length";
    c.log_x = c.log_y = true;
    c.width = kSlideWidth;
    c.height = kSlideHeight;
    c.type_scale = kSlideTypeScale;
    return c;
  };
  ChartSpec speed = base(speed_takeaway(r), "solver time per simulated second (s/s)");
  ChartSpec conv = base(convergence_takeaway(r), "time step h (s)");
  for (const std::string& m : study_methods_run(r)) {
    Series s;
    s.label = m;
    s.color = method_color(m);
    for (const StudyRow* row : ok_points(r, m)) {
      s.x.push_back(row->wall_s);
      s.y.push_back(row->error);
    }
    if (s.x.empty()) continue;  // failed at every h: the title says so
    speed.series.push_back(s);
    s.x.clear();
    for (const StudyRow* row : ok_points(r, m)) s.x.push_back(row->h);
    conv.series.push_back(s);
  }
  Series smooth;
  smooth.label = "no contact";
  for (const StudyRow& row : r.rows)
    if (row.method == "lecture-no-contact" && std::isfinite(row.error) && row.error > 0.0) {
      smooth.x.push_back(row.h);
      smooth.y.push_back(row.error);
    }
  if (!smooth.x.empty()) {
    conv.series.push_back(smooth);
    // The slope-1 guide through the check's smallest h, offset below it.
    const auto lo = std::min_element(smooth.x.begin(), smooth.x.end()) - smooth.x.begin();
    const double h_max = *std::max_element(smooth.x.begin(), smooth.x.end());
    Series guide;
    guide.label = "first order";
    guide.color = {0.55f, 0.55f, 0.55f};
    guide.markers = false;
    guide.dash = 9.0;
    for (double h : {smooth.x[lo], h_max}) {
      guide.x.push_back(h);
      guide.y.push_back(0.5 * smooth.y[lo] * h / smooth.x[lo]);
    }
    conv.series.push_back(guide);
  }
  return {{"study-slide-speed", speed}, {"study-slide-convergence", conv}};
}

}  // namespace invfree
