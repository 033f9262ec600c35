#include "solver/self_contact_filter.h"

#include "solver/ccd.h"

namespace invfree {

void self_contact_candidates_at(const SelfContact& c, const VecX& z, BroadPhaseGrid& grid) {
  const SelfContactTimer timer{c.cache->ms};
  point_edge_candidates(*c.boundary, z, c.params.dhat, grid, c.cache->pairs);
}

double self_contact_filter(const SelfContact& c, const VecX& z, const VecX& dir, double alpha_max,
                           BroadPhaseGrid& grid) {
  swept_point_edge_candidates(*c.boundary, z, dir, alpha_max, c.params.dhat, grid, c.cache->pairs);
  if (!c.ccd) return alpha_max;
  return self_contact_step(*c.boundary, c.cache->pairs, z, dir, alpha_max);
}

double self_contact_path_step(const SelfContact& c, const VecX& z, const VecX& trial,
                              VecX& scratch) {
  const SelfContactTimer timer{c.cache->ms};
  if (!c.ccd) return 1.0;
  scratch = trial - z;
  return self_contact_step(*c.boundary, c.cache->pairs, z, scratch, 1.0);
}

}  // namespace invfree
