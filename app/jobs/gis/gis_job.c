/* gis_job — the viewshed and track commands (gis_job.h). */
/* M_PI is XSI */
#define _XOPEN_SOURCE 700
#include "jobs/gis/gis_job.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "data/geo/dem.h"
#include "data/geo/geo.h"
#include "data/sky/sun.h"
#include "data/geo/terrain.h"
#include "data/geo/viewshed.h"
#include "data/geo/water.h"
#include "scene/scene.h"
#include "view/camera.h"
#include "view/path.h"

/* The texels a viewshed reads: the whole DEM, or with a radius only the window around the observer that holds
 * it (a 3 km radius on a 20000² DEM read and computed it all). */
static bool viewshed_window(const gis_options *o, double *col, double *row, int *x0, int *y0, int *w, int *h,
                            float **heights, dem_info *info, err_t *err)
{
    int W, H;
    double range[2];
    *x0 = *y0 = *w = *h = 0;
    if (!dem_probe(o->dem, &W, &H, range, info, err))
        return false;
    if (!info->georeferenced)
        return err_set(err, "the DEM '%s' has no georeferencing: a viewshed needs its spacing in metres and its place "
                            "on the Earth", o->dem);
    if (!geo_convert(o->dem, true, 1, &o->lon, &o->lat, col, row, err))
        return false;
    if (o->radius > 0 && *col > -1 && *col < W && *row > -1 && *row < H) { /* off the DEM: viewshed_compute says so */
        double rx = o->radius / info->spacing[0] + 1, rz = o->radius / info->spacing[1] + 1;
        int x1 = (int)fmin(W - 1, ceil(*col + rx)), y1 = (int)fmin(H - 1, ceil(*row + rz));
        *x0 = (int)fmax(0, floor(*col - rx)), *y0 = (int)fmax(0, floor(*row - rz));
        *w = x1 - *x0 + 1, *h = y1 - *y0 + 1;
        *col -= *x0, *row -= *y0;
    }
    return dem_read_window(o->dem, *x0, *y0, w, h, TERRAIN_MAX_SIDE, heights, info, err);
}

bool gis_viewshed_run(const gis_options *o, err_t *err)
{
    int x0, y0, w, h;
    float *heights = NULL;
    dem_info info = {0};
    double col = 0, row = 0;
    bool ok = viewshed_window(o, &col, &row, &x0, &y0, &w, &h, &heights, &info, err);
    unsigned char *out = ok ? util_alloc((size_t)w * (size_t)h, "the viewshed") : NULL;
    viewshed_desc d = {.heights = heights, .w = w, .h = h, .dx = info.spacing[0], .dz = info.spacing[1], .col = col,
                       .row = row, .observer_height = o->observer_height, .target_height = o->target_height,
                       .refraction = o->refraction, .curvature = !o->flat_earth, .radius = o->radius};
    viewshed_stats st;
    ok = ok && viewshed_compute(&d, out, &st, err);
    char earth[96], about[512];
    if (o->flat_earth)
        snprintf(earth, sizeof earth, "a flat Earth");
    else
        snprintf(earth, sizeof earth, "Earth curvature, refraction coefficient %.3f", o->refraction);
    snprintf(about, sizeof about,
             "viewshed from %.6f,%.6f (texel %.2f, %.2f), eye %.2f m above the ground, targets %.2f m; %s; 1 visible, "
             "0 hidden, 255 nodata%s (fathom %s)",
             o->lon, o->lat, col + x0, row + y0, o->observer_height, o->target_height, earth,
             o->radius > 0 ? " or beyond the radius" : "", FATHOM_VERSION);
    ok = ok && geo_write_mask(o->dem, o->output, x0, y0, w, h, out, about, err);
    if (ok) {
        size_t seen = st.visible + st.hidden;
        printf("%s: %zu of %zu texels visible (%.1f %%), %zu nodata; %.2f s on %d threads (%.1f pyramid nodes a "
               "texel); %d x %d texels from %d, %d\n",
               o->output, st.visible, seen, seen ? 100.0 * (double)st.visible / (double)seen : 0.0, st.nodata, st.seconds,
               st.threads, st.nodes_per_texel, w, h, x0, y0);
    }
    free(out);
    free(heights);
    return ok;
}

/* ---- lakes ------------------------------------------------------------------------------------- */

bool gis_water_run(const gis_options *o, err_t *err)
{
    int w, h;
    float *ground = NULL;
    dem_info info = {0};
    if (!dem_read(o->dem, TERRAIN_MAX_SIDE, &w, &h, &ground, &info, err))
        return false;
    bool ok = info.georeferenced ||
              err_set(err, "the DEM '%s' has no georeferencing: fathom water writes its lakes on the DEM's grid and "
                           "needs its CRS and spacing; give a GeoTIFF, .hgt or other georeferenced DEM", o->dem);
    size_t n = (size_t)w * (size_t)h;
    float *surface = ok ? util_alloc(n * sizeof *surface, "the lakes") : NULL;
    float *depth = ok ? util_alloc(n * sizeof *depth, "the lakes") : NULL;
    water_fill_desc d = {.ground = ground, .w = w, .h = h, .dx = info.spacing[0], .dz = info.spacing[1],
                         .min_depth = o->min_depth, .min_area = o->min_area};
    water_fill_stats st;
    double t0 = util_now();
    ok = ok && water_fill(&d, surface, &st, err);
    double secs = util_now() - t0;
    for (size_t c = 0; ok && c < n; c++)
        depth[c] = isnan(ground[c]) ? NAN : isnan(surface[c]) ? 0.0f : surface[c] - ground[c];
    char about[2][256]; /* the surface first: terrain.water draws band 1 */
    snprintf(about[0], sizeof about[0], "water surface height, metres (nodata where dry), lakes filled to their spill "
             "heights%s (fathom %s)", o->min_depth > 0 || o->min_area > 0 ? ", shallow or small ones left dry" : "",
             FATHOM_VERSION);
    snprintf(about[1], sizeof about[1], "water depth, metres (0 dry) (fathom %s)", FATHOM_VERSION);
    const float *bands[2] = {surface, depth};
    const char *descriptions[2] = {about[0], about[1]};
    ok = ok && geo_write_floats(o->dem, o->output, w, h, 2, bands, descriptions, err);
    if (ok)
        printf("%s: %zu lake%s (%zu left dry by --min-depth or --min-area), %zu texels under water (%.4g km²), %.4g m³, "
               "deepest %.2f m; %.2f s for %d x %d texels\n", o->output, st.lakes, st.lakes == 1 ? "" : "s", st.dropped,
               st.wet, (double)st.wet * d.dx * d.dz / 1e6, st.volume, st.deepest, secs, w, h);
    free(depth);
    free(surface);
    free(ground);
    return ok;
}

/* ---- tracks ------------------------------------------------------------------------------------ */

/* The DEM as its scene draws it: texels, spacing, exaggeration and the heights (metres). World x of
 * texel column c is (c + ½ − w/2)·dx (data/geo/terrain.h's contract), z likewise, y the height × ex. */
typedef struct frame {
    int w, h;
    double dx, dz, ex;
    float *heights;
    scene s;
} frame;

static bool frame_load(const gis_options *o, frame *f, err_t *err)
{
    char set[PATH_MAX_LEN + 32];
    const char *sets[65];
    snprintf(set, sizeof set, "terrain.heightmap=%s", o->dem);
    sets[0] = set;
    for (int i = 0; i < o->set_count; i++)
        sets[i + 1] = o->sets[i];
    if (!scene_load(o->scene ? o->scene : "dem", sets, o->set_count + 1, &f->s, err))
        return false;
    heightfield_desc d = {.path = o->dem, .spacing = {f->s.terrain.spacing[0], f->s.terrain.spacing[1]},
                          .exaggeration = f->s.terrain.exaggeration};
    double size[2], range[2], spacing[2];
    dem_info info;
    bool ok = heightfield_probe(&d, size, range, spacing, err) &&
              dem_read(o->dem, TERRAIN_MAX_SIDE, &f->w, &f->h, &f->heights, &info, err);
    if (!ok) {
        scene_free(&f->s);
        return false;
    }
    f->dx = spacing[0], f->dz = spacing[1], f->ex = f->s.terrain.exaggeration > 0 ? f->s.terrain.exaggeration : 1;
    return true;
}

static void frame_free(frame *f)
{
    free(f->heights);
    scene_free(&f->s);
}

/* The ground (metres, bilinear) under texel coordinates; NaN off the grid or over a hole. */
static double frame_ground(const frame *f, double c, double r)
{
    if (!(c >= 0 && r >= 0 && c <= f->w - 1 && r <= f->h - 1))
        return NAN;
    int i = (int)fmin(floor(c), f->w - 2), j = (int)fmin(floor(r), f->h - 2);
    double u = c - i, v = r - j;
    const float *p = f->heights + (size_t)j * (size_t)f->w + (size_t)i;
    return (p[0] * (1 - u) + p[1] * u) * (1 - v) + (p[f->w] * (1 - u) + p[f->w + 1] * u) * v;
}

/* A flight key: world position, the point it looks at, its time. */
typedef struct key {
    double p[3], at[3], t;
    double along; /* metres along the track from its first key */
} key;

/* Keys from the track's points inside the DEM: at least `gap` metres apart, each `height` above the
 * ground. Returns the count; *outside the points left out. */
static int track_keys(const gis_options *o, const frame *f, const geo_point *pts, const double *col,
                      const double *row, int n, double gap, key *k, int *outside)
{
    int m = 0;
    double dist = 0;
    *outside = 0;
    for (int i = 0; i < n; i++) {
        double g = frame_ground(f, col[i], row[i]);
        if (isnan(g)) {
            (*outside)++;
            continue;
        }
        double x = (col[i] + 0.5 - f->w / 2.0) * f->dx, z = (row[i] + 0.5 - f->h / 2.0) * f->dz;
        double step = m ? hypot(x - k[m - 1].p[0], z - k[m - 1].p[2]) : 0;
        bool last = i == n - 1;
        if (m && step < gap && !last)
            continue;
        if (m && step < 1e-6) /* the last point on top of the previous key */
            continue;
        dist += step;
        k[m++] = (key){{x, (g + o->height) * f->ex, z}, {0, 0, 0}, pts[i].time, dist};
    }
    return m;
}

/* The track's own times where it has them: a key without one (a point whose <time> is missing) takes the time
 * its distance along says between the timed keys around it, or beyond the ends at `speed`. False (distance /
 * speed for all) when fewer than two keys have times or the times do not increase. */
static bool own_times(key *k, int m, double speed)
{
    int first = -1, last = -1;
    for (int i = 0; i < m; i++)
        if (!isnan(k[i].t)) {
            if (last >= 0 && !(k[i].t > k[last].t))
                return false;
            first = first < 0 ? i : first, last = i;
        }
    if (first < 0 || first == last)
        return false;
    for (int i = 0, a = first; i < m; i++) {
        if (!isnan(k[i].t)) {
            a = i;
            continue;
        }
        int b = i + 1;
        while (b < m && isnan(k[b].t))
            b++;
        if (i < first || b >= m) { /* before the first time or after the last: at the track's speed */
            int e = i < first ? first : last;
            k[i].t = k[e].t + (k[i].along - k[e].along) / speed;
        } else { /* between two: by distance along, or evenly where the keys do not move */
            double span = k[b].along - k[a].along, f = span > 0 ? (k[i].along - k[a].along) / span
                                                                 : (double)(i - a) / (b - a);
            k[i].t = k[a].t + (k[b].t - k[a].t) * f;
        }
    }
    for (int i = 1; i < m; i++)
        if (!(k[i].t > k[i - 1].t))
            return false;
    return true;
}

/* Times (the track's own, a missing one filled in by own_times, else distance / speed) and where each key
 * looks: the track `ahead` metres on, down to the ground there. */
static void track_times_and_views(const gis_options *o, const frame *f, key *k, int m)
{
    bool own = own_times(k, m, o->speed);
    double t0 = k[0].t, ahead = fmax(4 * o->height, 10 * fmax(f->dx, f->dz));
    for (int i = 0; i < m; i++)
        k[i].t = own ? k[i].t - t0 : k[i].along / o->speed;
    for (int i = 0, j = 0; i < m; i++) {
        while (j < m - 1 && k[j].along < k[i].along + ahead)
            j++;
        double dx = k[j].p[0] - k[i].p[0], dz = k[j].p[2] - k[i].p[2], len = hypot(dx, dz);
        if (len < 1e-6) { /* the end: keep the last heading */
            dx = k[i].p[0] - k[i > 0 ? i - 1 : 0].p[0], dz = k[i].p[2] - k[i > 0 ? i - 1 : 0].p[2];
            len = fmax(hypot(dx, dz), 1e-9);
        }
        double ax = k[i].p[0] + dx / len * ahead, az = k[i].p[2] + dz / len * ahead;
        double g = frame_ground(f, ax / f->dx + f->w / 2.0 - 0.5, az / f->dz + f->h / 2.0 - 0.5);
        k[i].at[0] = ax, k[i].at[2] = az;
        k[i].at[1] = isnan(g) ? k[i].p[1] - o->height * f->ex : g * f->ex;
    }
}

static bool write_flight(const char *out, const key *k, int m, err_t *err)
{
    strbuf b = {0};
    sb_printf(&b, "{ \"keys\": [\n");
    for (int i = 0; i < m; i++)
        sb_printf(&b, "  { \"time\": %.3f, \"position\": [%.3f, %.3f, %.3f], \"look_at\": [%.3f, %.3f, %.3f] }%s\n",
                  k[i].t, k[i].p[0], k[i].p[1], k[i].p[2], k[i].at[0], k[i].at[1], k[i].at[2], i + 1 < m ? "," : "");
    sb_printf(&b, "] }\n");
    path p; /* what render --path will read: checked before it is written */
    bool ok = path_parse(b.data, out, &p, err);
    if (ok)
        path_free(&p);
    ok = ok && util_write_text_atomic(out, b.data, "the flight", err);
    sb_free(&b);
    return ok;
}

static bool track_to_flight(const gis_options *o, frame *f, err_t *err)
{
    geo_point *pts;
    int n;
    if (!geo_track_read(o->input, &pts, &n, err))
        return false;
    double *lon = malloc(sizeof(double) * 4 * (size_t)n), *lat = lon + n, *col = lat + n, *row = col + n;
    for (int i = 0; i < n; i++)
        lon[i] = pts[i].lon, lat[i] = pts[i].lat;
    key *k = malloc(sizeof(key) * (size_t)n);
    int m = 0, outside = 0;
    bool ok = geo_convert(o->dem, true, n, lon, lat, col, row, err);
    for (double gap = fmax(f->dx, f->dz); ok; gap *= 2) { /* a flight holds PATH_MAX_KEYS keys at most */
        m = track_keys(o, f, pts, col, row, n, gap, k, &outside);
        if (m <= PATH_MAX_KEYS)
            break;
    }
    if (ok && m < 2)
        ok = err_set(err, "the track '%s' has %d of its %d points on the DEM '%s': a flight needs two (is it in "
                          "the DEM's area?)", o->input, m, n, o->dem);
    if (ok) {
        track_times_and_views(o, f, k, m);
        if (k[m - 1].t > PATH_MAX_TIME)
            ok = err_set(err, "the track lasts %.0f s: a flight lasts at most a day (%.0f s); give --speed for a faster "
                              "one", k[m - 1].t, PATH_MAX_TIME);
    }
    ok = ok && write_flight(o->output, k, m, err);
    double km = ok ? 0.001 * k[m - 1].along : 0;
    if (ok)
        printf("%s: %d keys from %d track points (%d outside the DEM), %.0f s, %.1f km, %.0f m above the ground\n",
               o->output, m, n, outside, k[m - 1].t, km, o->height);
    free(k);
    free(lon);
    free(pts);
    return ok;
}

/* Points a flight becomes at most: a GPX of 10^6 points is ~100 MB, beyond what GPS tools open. */
enum { TRACK_POINTS_MAX = 1000000 };

/* When the flight starts: the scene's sun date and hour when it sets one (the day it shows), else the flight's
 * own time base, its seconds from 1970-01-01T00:00:00Z (the same track every run, never the clock's "now"). */
static double flight_start(const scene *s, bool *sun)
{
    double t;
    *sun = s->sun.on && sun_time(s->sun.date, s->sun.hour, s->sun.utc_offset, &t);
    return *sun ? t : 0;
}

static bool flight_to_track(const gis_options *o, frame *f, err_t *err)
{
    path p;
    if (!path_load(o->path, &p, err))
        return false;
    bool sun;
    double t0 = p.keys[0].time, t1 = p.keys[p.count - 1].time, start = flight_start(&f->s, &sun);
    double points = floor((t1 - t0) * o->fps + 1e-9) + 1;
    if (points > TRACK_POINTS_MAX) {
        path_free(&p);
        return err_set(err, "%s: %.0f s of flight at --fps %g is %.0f points, more than the %d a track holds here: "
                            "lower --fps", o->path, t1 - t0, o->fps, points, TRACK_POINTS_MAX);
    }
    int n = points < 2 ? 2 : (int)points;
    geo_point *pts = util_alloc(sizeof *pts * (size_t)n, "the track's points");
    double (*cam)[3] = util_alloc(sizeof *cam * (size_t)n, "the track's cameras");
    double *buf = util_alloc(sizeof(double) * 4 * (size_t)n, "the track's coordinates");
    double *col = buf, *row = buf + n, *lon = buf + 2 * n, *lat = buf + 3 * n;
    for (int i = 0; i < n; i++) {
        double t = i == n - 1 ? t1 : t0 + i / o->fps;
        path_sample ps;
        path_eval(&p, t, &ps);
        col[i] = ps.position[0] / f->dx + f->w / 2.0 - 0.5;
        row[i] = ps.position[2] / f->dz + f->h / 2.0 - 0.5;
        pts[i] = (geo_point){0, 0, ps.position[1] / f->ex, start + (t - t0)};
        /* camera.h: yaw 0 looks north (−Z) and grows turning left; KML: heading clockwise from north,
         * tilt 0 looking straight down and 90 at the horizon */
        double heading = fmod(-ps.yaw * 180 / M_PI + 720, 360);
        cam[i][0] = heading, cam[i][1] = 90 + ps.pitch * 180 / M_PI, cam[i][2] = ps.roll * 180 / M_PI;
    }
    bool ok = geo_convert(o->dem, false, n, col, row, lon, lat, err);
    for (int i = 0; ok && i < n; i++)
        pts[i].lon = lon[i], pts[i].lat = lat[i];
    const char *base = strrchr(o->path, '/');
    ok = ok && geo_track_write(o->output, base ? base + 1 : o->path, pts, (const double (*)[3])cam, n, err);
    if (ok)
        printf("%s: %d points, %.1f s of the flight at %g a second, from %s; times %s\n", o->output, n, t1 - t0, o->fps,
               o->path, sun ? "from the scene's sun date and hour" : "the flight's own seconds from 1970-01-01T00:00:00Z "
                                                                       "(give the scene a sun block for a real day)");
    free(buf);
    free(cam);
    free(pts);
    path_free(&p);
    return ok;
}

bool gis_track_run(const gis_options *o, err_t *err)
{
    frame f = {0};
    if (!frame_load(o, &f, err))
        return false;
    bool ok = o->input ? track_to_flight(o, &f, err) : flight_to_track(o, &f, err);
    frame_free(&f);
    return ok;
}
