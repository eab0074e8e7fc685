/* route — a recorded flight whose spline stays out of solids (route.h). */
#include "view/route.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { PER_SECOND = 240, MAX_POINTS = 1 << 14, CHUNK = 64 /* points a probe at most */ };
static const double CLEAR_REL = 2 * 4.76837158e-7; /* twice quality.h's PRECISION_REL, flight.c's test */

double route_first_dip(const path_camera *keys, int n, double t0, double t1, camera_probe_fn probe, void *ctx)
{
    strbuf text = {0};
    path p;
    err_t e;
    path_text_from_cameras(keys, n, &text);
    bool ok = path_parse(text.data, "the recorded flight", &p, &e);
    sb_free(&text);
    if (!ok)
        return t0; /* no spline to fly: as bad as a dip */
    int m = (int)fmin(MAX_POINTS, fmax(2.0, ceil((t1 - t0) * PER_SECOND)));
    double pts[CHUNK * 3], dip = -1;
    float d[CHUNK];
    for (int i0 = 0; i0 < m && dip < 0; i0 += CHUNK) {
        int k = m - i0 < CHUNK ? m - i0 : CHUNK;
        for (int j = 0; j < k; j++) {
            path_sample s;
            path_eval(&p, t0 + (t1 - t0) * (i0 + j) / (m - 1), &s);
            memcpy(pts + 3 * j, s.position, sizeof s.position);
        }
        probe(ctx, pts, k, d);
        for (int j = 0; j < k && dip < 0; j++) {
            const double *q = pts + 3 * j;
            if ((double)d[j] < CLEAR_REL * (1 + fabs(q[0]) + fabs(q[1]) + fabs(q[2])))
                dip = t0 + (t1 - t0) * (i0 + j) / (m - 1);
        }
    }
    path_free(&p);
    return dip;
}

/* Each key from `from` on timed again after the one before it (path_next_key_time). */
static void retime(path_camera *keys, int n, int from, double speed)
{
    for (int i = from > 1 ? from : 1; i < n; i++)
        keys[i].time = path_next_key_time(keys, i, keys[i].position, speed);
}

int route_clear(path_camera *keys, int *n, int max, const path_camera *trail, int trail_n, double speed,
                camera_probe_fn probe, void *ctx)
{
    int first = *n - 2; /* the key before the new one: the stretch from it on is ours to split */
    if (first < 0)
        return 0;
    /* the trail index each key of the stretch stands at: the key before, −1; the new key, trail_n */
    int at[ROUTE_MAX_ADDED + 2] = {-1, trail_n}, added = 0;
    double t0 = keys[first > 0 ? first - 1 : 0].time; /* the new key bends the segment before too */
    for (;;) {
        double dip = route_first_dip(keys, *n, t0, keys[*n - 1].time, probe, ctx);
        if (dip < 0)
            return added;
        int a = 0; /* the stretch's segment [first + a, first + a + 1] that holds the dip */
        while (first + a + 1 < *n - 1 && keys[first + a + 1].time <= dip)
            a++;
        bool inside_stretch = dip >= keys[first].time;
        if (!inside_stretch || at[a + 1] - at[a] < 2 || added == ROUTE_MAX_ADDED || *n == max) {
            *n = first + 1; /* the trail cannot clear it: the new key and what was added for it go */
            return -1;
        }
        int mid = (at[a] + at[a + 1]) / 2, k = first + a + 1;
        memmove(keys + k + 1, keys + k, sizeof *keys * (size_t)(*n - k));
        memmove(at + a + 2, at + a + 1, sizeof *at * (size_t)(added + 1 - a));
        keys[k] = trail[mid];
        at[a + 1] = mid;
        (*n)++, added++;
        retime(keys, *n, k, speed);
    }
}
