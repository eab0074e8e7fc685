/* route — a recorded flight whose spline stays out of solids. The window records keys where the user
 * presses N, but the spline through them is not the way the camera flew: between two keys it can cut
 * through the solid the camera slid around. Where it dips into a surface, keys are added from the
 * camera's own trail since the last key (which the slide rule kept clear), halving the offending stretch
 * until the spline clears it, the way `fathom render --path` checks it. Pure (the distance bound comes
 * from the caller, as for camera_slide). */
#ifndef FATHOM_ROUTE_H
#define FATHOM_ROUTE_H

#include "view/camera.h"
#include "view/path.h"

enum { ROUTE_MAX_ADDED = 16 };

/* keys[0 … *n−1] end with the key just added (time from path_next_key_time at `speed`); trail[0 …
 * trail_n−1] is the camera between the key before it and it, in order. Adds at most ROUTE_MAX_ADDED
 * keys from the trail (never past `max` keys in all), retiming the keys after each, until the spline
 * clears every surface from the key before last on (probe: the distance bound, as camera_slide's).
 * Returns the keys added; −1 when the trail cannot clear it, with the new key taken back (*n one
 * less): the keys before it, whose spline was clear, are as they were. */
int route_clear(path_camera *keys, int *n, int max, const path_camera *trail, int trail_n, double speed,
                camera_probe_fn probe, void *ctx);

/* The spline through keys[0 … n−1]: the first time in [t0, t1] where it dips into a surface (the
 * bound below twice a float's resolution at the point, as the flight's own check), or −1 when clear. */
double route_first_dip(const path_camera *keys, int n, double t0, double t1, camera_probe_fn probe, void *ctx);

#endif
