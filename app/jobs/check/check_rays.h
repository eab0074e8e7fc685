/* check_rays — check-formula's rays through the set (check_rays.c), called by check.c. */
#ifndef FATHOM_CHECK_RAYS_H
#define FATHOM_CHECK_RAYS_H

#include "jobs/check/check_probe.h"

/* Rays through the set (check_rays.c): first_rays at random, half of them toward `near`, then rounds
 * around the worst; each estimate along a ray against the distance to the ray's first crossing. */
bool check_rays(const scene *s, unsigned *seed, int first_rays, const check_targets *near, formula_check *c, err_t *err);

#endif
