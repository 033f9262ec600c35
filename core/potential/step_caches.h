// What the terms of one step keep between calls: self-contact's candidate pairs, its
// lagged friction pairs and Hessian blocks, the broad phase's grid and the time spent
// (SelfContactCache, self_contact.h). Owned by the step's workspace and passed by
// reference to every sum that may write it (TermPoint::caches).
#pragma once

#include "collision/broad_phase.h"
#include "potential/self_contact.h"

namespace invfree {

struct StepCaches {
  SelfContactCache contact;
  BroadPhaseGrid grid;  // the broad phase's cells, reused
  VecX scratch;         // a path's direction (self-contact's path_step)
};

}  // namespace invfree
