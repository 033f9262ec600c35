// How a run ended (the stability table's classes) and the checks that decide it.
//   ok, inverted (det F <= 0), penetrated (a node on or through a plane), non-finite,
//   newton-failed (iteration cap, no descent, or a broken-down linear solve),
//   blew-up (energy growth the scene cannot supply, or nodes far outside any place the
//   scene could carry them), n/a (the method cannot start the scene at all), and
//   inverted-allowed: not a failure - a model that may invert by design (linear, ARAP,
//   stable neo-Hookean) reached det F <= 0 and the run went on to its end without failing.
// Blow-up criterion. Energy E = kinetic + elastic + gravity (core total_energy, barrier
// excluded; the barrier energy is >= 0, so this only under-counts). Physically
//   E(t) - E_floor <= E(0) - E_floor + W_ceiling(t)
// where E_floor is the gravity potential with every node at the ground (kinetic and
// elastic energy are >= 0) and W_ceiling the work the descending ceiling has done
// (friction and implicit Euler only remove energy). A run blew up when the left side
// exceeds `factor` (default 10) times the right side. The right side is never taken below
// a tiny floor, so a scene at rest without gravity does not trip on rounding.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "simulation.h"

namespace invfree {

enum class Verdict {
  Ok,
  Inverted,
  Penetrated,
  NonFinite,
  NewtonFailed,
  BlewUp,
  NotApplicable,
  Intersected,
  InvertedAllowed
};

const char* verdict_name(Verdict v);  // "ok", "inverted", ..., "n/a"
Verdict verdict_from_status(StepStatus s);

// Pure form of the energy criterion (all in joules).
bool energy_exceeds_budget(double energy, double floor, double initial, double ceiling_work,
                           double factor, double minimum_budget);

// Tracks one run: call `start` on the initial state and `after_step` after every accepted
// step; `after_step` returns Ok or BlewUp/Inverted with a reason in `why`.
struct RunMonitor {
  double factor = 10.0;
  double initial_energy = 0.0;
  double floor = 0.0;
  double ceiling_work = 0.0;
  double ceiling_force = 0.0;  // downward push of the ceiling on the nodes at the last state
  double previous_ceiling = 0.0;
  double minimum_budget = 0.0;
  double box_radius = 0.0;
  Vec2 box_center = Vec2::Zero();
  bool inversion_is_failure = true;  // false: det F <= 0 is not looked at (the study)
  // With inversion_is_failure: an inversion is recorded (inverted_step, inverted_why) and the
  // run goes on, for the models that may invert by design (methods.h, inversion_allowed).
  bool inversion_allowed = false;
  long inverted_step = -1;
  std::string inverted_why;
  double min_det_f = INFINITY;    // over the run, where det F is looked at
  bool started_inverted = false;  // an invertible model may start inverted and recover
  bool recovered = true;

  void start(const Simulation& sim, double duration);
  Verdict after_step(const Simulation& sim, std::string* why);
  // At the end of a run: a start that never recovered from inversion is a failure.
  Verdict at_end(std::string* why) const;
};

// Total downward force of the ceiling barrier on the nodes (N), and the gravity floor.
double ceiling_push(const Simulation& sim);
double gravity_floor(const Simulation& sim);

}  // namespace invfree
