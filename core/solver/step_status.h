// Outcome of a time step, shared by the solver, the tools and the tests.
#pragma once

#include "enum_names.h"

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

inline constexpr EnumName<StepStatus> kStepStatusNames[] = {
    {StepStatus::Ok, "ok"},
    {StepStatus::NewtonFailed, "newton-failed"},
    {StepStatus::LinearSolveFailed, "linear-solve-failed"},
    {StepStatus::NonFinite, "non-finite"},
    {StepStatus::Inverted, "inverted"},
    {StepStatus::Penetrated, "penetrated"},
    {StepStatus::Intersected, "intersected"},
};

inline const char* step_status_name(StepStatus s) {
  return enum_name(kStepStatusNames, s);
}

}  // namespace invfree
