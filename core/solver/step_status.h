// Outcome of a time step, shared by the solver, the tools and the tests.
#pragma once

namespace invfree {

enum class StepStatus {
  Ok,
  NewtonFailed,       // iteration cap reached, or no descent along the Newton direction
  LinearSolveFailed,  // the factorisation broke down or produced a non-finite direction
  NonFinite,          // positions or velocities became NaN/inf
  Inverted,           // a triangle reached det F <= 0 under a model that forbids it
  Penetrated,         // a node reached or crossed the ground or the ceiling
  Intersected,        // two boundary edges intersect (self-contact on)
};

inline const char* step_status_name(StepStatus s) {
  switch (s) {
    case StepStatus::Ok:
      return "ok";
    case StepStatus::NewtonFailed:
      return "newton-failed";
    case StepStatus::LinearSolveFailed:
      return "linear-solve-failed";
    case StepStatus::NonFinite:
      return "non-finite";
    case StepStatus::Inverted:
      return "inverted";
    case StepStatus::Penetrated:
      return "penetrated";
    case StepStatus::Intersected:
      return "intersected";
  }
  return "?";
}

}  // namespace invfree
