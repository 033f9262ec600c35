// Self-contact in the line search: the broad phase that fills the self-contact term's
// candidate list (potential/self_contact.h) and the CCD filter (solver/ccd.h) over it.
// Inputs: the term, the current point z, a direction (or a trial point), the broad phase's
// grid (reused). Outputs: the candidate list in the term's cache, the largest
// collision-free step.
#pragma once

#include "collision/broad_phase.h"
#include "potential/self_contact.h"

namespace invfree {

// Candidates around the point z (no motion): the start of a step.
void self_contact_candidates_at(const SelfContact& c, const VecX& z, BroadPhaseGrid& grid);
// Candidates over z -> z + alpha_max dir, then the largest alpha in [0, alpha_max] that
// moves no boundary node through a boundary edge (additive CCD; alpha_max when the term's
// ccd is off).
double self_contact_filter(const SelfContact& c, const VecX& z, const VecX& dir, double alpha_max,
                           BroadPhaseGrid& grid);
// The largest fraction of the straight motion z -> trial that is collision-free, over the
// current candidates (a trial the friction-crossing stop moved off the line z + alpha p;
// each node's new position stays inside its path's box, so the candidates still hold).
double self_contact_path_step(const SelfContact& c, const VecX& z, const VecX& trial,
                              VecX& scratch);

}  // namespace invfree
