#include "app/study/verdict.h"

#include <algorithm>
#include <cmath>

#include "app/body_extent.h"
#include "app/format_number.h"
#include "enum_names.h"
#include "make_terms.h"

namespace invfree {

namespace {
constexpr EnumName<Verdict> kVerdictNames[] = {
    {Verdict::Ok, "ok"},
    {Verdict::Inverted, "inverted"},
    {Verdict::Penetrated, "penetrated"},
    {Verdict::NonFinite, "non-finite"},
    {Verdict::NewtonFailed, "newton-failed"},
    {Verdict::BlewUp, "blew-up"},
    {Verdict::NotApplicable, "n/a"},
    {Verdict::Intersected, "intersected"},
    {Verdict::InvertedAllowed, "inverted-allowed"},
};
}  // namespace

const char* verdict_name(Verdict v) {
  return enum_name(kVerdictNames, v);
}

Verdict verdict_from_status(StepStatus s) {
  switch (s) {
    case StepStatus::Ok:
      return Verdict::Ok;
    case StepStatus::NewtonFailed:
    case StepStatus::LinearSolveFailed:
      return Verdict::NewtonFailed;
    case StepStatus::NonFinite:
      return Verdict::NonFinite;
    case StepStatus::Inverted:
      return Verdict::Inverted;
    case StepStatus::Penetrated:
      return Verdict::Penetrated;
    case StepStatus::Intersected:
      return Verdict::Intersected;
  }
  return Verdict::NonFinite;
}

bool energy_exceeds_budget(double energy, double floor, double initial, double ceiling_work,
                           double factor, double minimum_budget) {
  if (!std::isfinite(energy)) return true;
  const double budget = std::max(initial - floor + std::max(ceiling_work, 0.0), minimum_budget);
  return energy - floor > factor * budget;
}

double ceiling_push(const Simulation& sim) {
  if (!sim.scene.has_ceiling) return 0.0;
  return ceiling_barrier_of(sim).push(sim.x.data(), sim.mesh.node_count(), sim.ceiling_y);
}

double gravity_floor(const Simulation& sim) {
  const SceneDef& s = sim.scene;
  if (!s.has_gravity) return 0.0;
  // The lowest gravity potential the nodes can reach: all at the ground (if the gravity
  // points into it), otherwise at the lowest point seen so far, which the caller tracks.
  double mass = 0.0;
  for (double m : sim.node_mass) mass += m;
  double lowest = s.has_ground ? s.ground_y : sim.x[1];
  if (!s.has_ground)
    for (int i = 0; i < sim.mesh.node_count(); ++i) lowest = std::min(lowest, sim.x[2 * i + 1]);
  // total_energy's gravity term is -sum m g . x; its minimum over y >= lowest with x fixed
  // in the direction of g's horizontal part is unbounded unless g is vertical, which every
  // scene has; use the vertical part.
  return -mass * s.gravity.y() * lowest;
}

void RunMonitor::start(const Simulation& sim, double duration) {
  initial_energy = total_energy(sim);
  floor = gravity_floor(sim);
  ceiling_work = 0.0;
  ceiling_force = ceiling_push(sim);
  previous_ceiling = sim.ceiling_y;
  double mass = 0.0;
  for (double m : sim.node_mass) mass += m;
  const double L = scene_length_scale(sim.scene);
  minimum_budget = 1e-6 * mass * L * L;  // 1e-6 J per kg m^2 s^-2: far below any real motion
  // The box follows the scene: around every node's start (bodies far apart are one
  // scene), grown by 10 L and by how far the fastest node and gravity could carry a node
  // in the run (every body's own velocity, not only initial.velocity).
  Eigen::AlignedBox2d start_box;
  double speed = 0.0;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    start_box.extend(Vec2(sim.x.segment<2>(2 * i)));
    speed = std::max(speed, sim.v.segment<2>(2 * i).norm());
  }
  box_center = start_box.center();
  const double g = sim.scene.has_gravity ? sim.scene.gravity.norm() : 0.0;
  box_radius = 0.5 * start_box.sizes().maxCoeff() + 10.0 * L + speed * duration +
               0.5 * g * duration * duration;
  const auto det = triangle_det_f(sim);
  started_inverted = std::any_of(det.begin(), det.end(), [](double d) { return !(d > 0.0); });
  recovered = !started_inverted;
  for (double d : det) min_det_f = std::min(min_det_f, d);
}

Verdict RunMonitor::after_step(const Simulation& sim, std::string* why) {
  // Energy supplied by the ceiling over this step: its push (the larger of the two ends,
  // an upper bound for a monotone barrier force) times how far it moved down.
  const double push = ceiling_push(sim);
  if (sim.scene.has_ceiling) {
    ceiling_work += std::max(push, ceiling_force) * std::max(0.0, previous_ceiling - sim.ceiling_y);
    previous_ceiling = sim.ceiling_y;
  }
  ceiling_force = push;
  if (!sim.scene.has_ground) floor = std::min(floor, gravity_floor(sim));
  for (int i = 0; i < sim.mesh.node_count(); ++i)
    if ((sim.x.segment<2>(2 * i) - box_center).lpNorm<Eigen::Infinity>() > box_radius) {
      *why = "node " + std::to_string(i) + " left the bounding box (" +
             format_for_people(box_radius) + " m around the nodes' start)";
      return Verdict::BlewUp;
    }
  const double e = total_energy(sim);
  if (energy_exceeds_budget(e, floor, initial_energy, ceiling_work, factor, minimum_budget)) {
    *why = "energy " + format_for_people(e - floor) + " J above the floor exceeds " +
           format_for_people(factor) + "\u00d7 what the start and the ceiling supplied (" +
           format_for_people(initial_energy - floor + ceiling_work) + " J)";
    return Verdict::BlewUp;
  }
  if (!inversion_is_failure) return Verdict::Ok;
  const auto det = triangle_det_f(sim);
  for (double d : det) min_det_f = std::min(min_det_f, d);
  const bool inverted = std::any_of(det.begin(), det.end(), [](double d) { return !(d > 0.0); });
  if (!inverted) {
    recovered = true;
  } else if (recovered && inversion_allowed) {
    if (inverted_step < 0) {
      inverted_step = sim.step_count;
      inverted_why = "a triangle reached det F <= 0, which the model allows; the run went on";
    }
  } else if (recovered) {
    *why = "a triangle reached det F <= 0";
    return Verdict::Inverted;
  }
  return Verdict::Ok;
}

Verdict RunMonitor::at_end(std::string* why) const {
  if (recovered || !inversion_is_failure || inversion_allowed) return Verdict::Ok;
  *why = "started inverted and never recovered (det F <= 0 at the end)";
  return Verdict::Inverted;
}

}  // namespace invfree
