/* Camera maths against double-precision expectations. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"

#include "view/camera.h"

static const double TOL = 2e-6;

static void look_at_points_forward(void **st)
{
    (void)st;
    const float targets[][3] = {{0, 0, -1}, {3, 1, 2}, {-5, -2, 0.5f}, {0.1f, 7, 0}};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        double eye[3] = {1, 2, 3}, at[3] = {targets[i][0], targets[i][1], targets[i][2]};
        camera c = camera_look_at(eye, at, 1.0f);
        camera_basis b = camera_get_basis(&c);
        double d[3], len = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = (double)targets[i][k] - eye[k];
            len += d[k] * d[k];
        }
        len = sqrt(len);
        for (int k = 0; k < 3; k++)
            assert_near(b.forward[k], d[k] / len, TOL);
    }
}

static void default_orientation(void **st)
{
    (void)st;
    camera c = {.fov_y = 1.0f};
    camera_basis b = camera_get_basis(&c);
    /* yaw = pitch = 0 looks down −Z with +X to the right and +Y up (right-handed, Y up) */
    assert_near(b.forward[2], -1.0, TOL);
    assert_near(b.right[0], 1.0, TOL);
    assert_near(b.up[1], 1.0, TOL);
}

static void basis_is_orthonormal_and_level(void **st)
{
    (void)st;
    for (int i = 0; i < 200; i++) {
        camera c = {.yaw = (float)i * 0.37f - 30.0f, .pitch = ((float)(i % 41) / 20.0f - 1.0f) * CAMERA_MAX_PITCH};
        camera_basis b = camera_get_basis(&c);
        assert_near(glm_vec3_norm(b.forward), 1.0, TOL);
        assert_near(glm_vec3_norm(b.right), 1.0, TOL);
        assert_near(glm_vec3_norm(b.up), 1.0, TOL);
        assert_near(glm_vec3_dot(b.forward, b.right), 0.0, TOL);
        assert_near(glm_vec3_dot(b.forward, b.up), 0.0, TOL);
        assert_near(b.right[1], 0.0, TOL); /* no roll */
        vec3 cross;
        glm_vec3_cross(b.right, b.up, cross); /* right × up = −forward in a right-handed frame */
        for (int k = 0; k < 3; k++)
            assert_near(cross[k], -b.forward[k], TOL);
    }
}

static void rays_span_the_field_of_view(void **st)
{
    (void)st;
    const double fov = 50.0 * GLM_PI / 180.0;
    camera c = camera_look_at((double[3]){0, 0, 0}, (double[3]){0, 0, -1}, (float)fov);
    const int w = 97, h = 61; /* odd: the centre pixel's centre is the image centre */
    vec3 d;
    camera_ray(&c, w, h, 48, 30, d);
    assert_near(d[2], -1.0, TOL);
    /* pixel centre (x, y) → tan of its angles = (2(x+.5)/w − 1) tan(fov/2) · (w/h, 1) */
    const int px[][2] = {{0, 0}, {96, 60}, {10, 50}, {70, 3}};
    for (size_t i = 0; i < sizeof px / sizeof px[0]; i++) {
        camera_ray(&c, w, h, (float)px[i][0], (float)px[i][1], d);
        double t = tan(fov / 2);
        double sx = (2.0 * (px[i][0] + 0.5) / w - 1.0) * t * w / h, sy = (2.0 * (px[i][1] + 0.5) / h - 1.0) * t;
        double n = sqrt(1 + sx * sx + sy * sy);
        assert_near(d[0], sx / n, TOL);
        assert_near(d[1], sy / n, TOL); /* y counts up from the bottom row */
        assert_near(d[2], -1.0 / n, TOL);
    }
    assert_near(camera_pixel_angle(&c, h), 2 * tan(fov / 2) / h, TOL);
}

static void moving_and_turning(void **st)
{
    (void)st;
    camera c = camera_look_at((double[3]){0, 1, 0}, (double[3]){0, 1, -1}, 1.0f);
    camera_input fwd = {.move = {0, 0, 1}};
    camera_update(&c, &fwd, 0.5f, 2.0f, 0.01f);
    assert_near(c.position[2], -1.0, TOL);
    camera_input fast_up = {.move = {0, 1, 0}, .fast = true};
    camera_update(&c, &fast_up, 0.25f, 1.0f, 0.01f);
    assert_near(c.position[1], 2.0, TOL); /* Shift: 4× */
    /* the mouse moves right: turn right, from −Z toward +X */
    camera_input look = {.look = {100, 0}};
    camera_update(&c, &look, 0.0f, 1.0f, 0.005f);
    camera_basis b = camera_get_basis(&c);
    assert_near(b.forward[0], sin(0.5), TOL);
    assert_near(b.forward[2], -cos(0.5), TOL);
    /* looking far down clamps short of straight down */
    camera_input down = {.look = {0, 1e6f}};
    camera_update(&c, &down, 0.0f, 1.0f, 0.01f);
    assert_near(c.pitch, -CAMERA_MAX_PITCH, TOL);
}

/* The worlds the slide rule flies through, one per kind of program, each a distance bound in double
 * with an exact inside test: solids (csg: spheres, boxes and a thin wall, exact distances), a fractal
 * (the Mandelbulb: a distance estimate, a bound at its step factor 0.9; inside = the orbit stays
 * bounded) and a terrain (y − h(x, z) over the slope bound: a Lipschitz bound; inside = below h). */
typedef enum world_kind { WORLD_SOLIDS, WORLD_FRACTAL, WORLD_TERRAIN, WORLD_PLANE } world_kind;

static double solids(const double p[3])
{
    static const double SPHERES[][4] = {{0, 0, 0, 1}, {3, 0.5, -2, 0.7}, {-2.5, 1, 1.5, 0.4}, {0.5, -3, 0.5, 1.5}};
    double d = INFINITY;
    for (int i = 0; i < 4; i++)
        d = fmin(d, sqrt(pow(p[0] - SPHERES[i][0], 2) + pow(p[1] - SPHERES[i][1], 2) + pow(p[2] - SPHERES[i][2], 2)) -
                        SPHERES[i][3]);
    /* a thin wall: |x - 1.8| < 0.01 for |y|, |z| < 4 */
    double q[3] = {fabs(p[0] - 1.8) - 0.01, fabs(p[1]) - 4, fabs(p[2]) - 4}, out = 0, in = -INFINITY;
    for (int i = 0; i < 3; i++)
        out += fmax(q[i], 0) * fmax(q[i], 0), in = fmax(in, q[i]);
    return fmin(d, sqrt(out) + fmin(in, 0));
}

enum { BULB_ITERATIONS = 10 };
static const double BULB_POWER = 8, BULB_STEP = 0.9, BULB_BOUND = 1.6;

/* The Mandelbulb's estimate ½ ln r · r / dr (White and Nylander's triplex power, Y up), with whether
 * the orbit stayed bounded (inside). */
static double bulb(const double c[3], bool *inside)
{
    double z[3] = {c[0], c[1], c[2]}, dr = 1, r = 0;
    for (int i = 0; i < BULB_ITERATIONS; i++) {
        r = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
        if (r > 2)
            break;
        double theta = r > 0 ? acos(fmin(fmax(z[1] / r, -1), 1)) * BULB_POWER : 0;
        double phi = atan2(z[2], z[0]) * BULB_POWER, rn = pow(r, BULB_POWER);
        dr = BULB_POWER * pow(r, BULB_POWER - 1) * dr + 1;
        z[0] = rn * sin(theta) * cos(phi) + c[0];
        z[1] = rn * cos(theta) + c[1];
        z[2] = rn * sin(theta) * sin(phi) + c[2];
    }
    r = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    *inside = r <= 2;
    return *inside ? 0 : 0.5 * log(r) * r / dr;
}

static double terrain_height(double x, double z) { return 0.6 * sin(1.3 * x) * cos(0.9 * z) + 0.25 * sin(3.1 * x + 2.3 * z); }
/* |∇h| ≤ 0.6 · √(1.3² + 0.9²) + 0.25 · √(3.1² + 2.3²) < 1.95: the vertical gap over √(1 + 1.95²) bounds the distance */
static const double TERRAIN_SLOPE = 1.95;

static double world(world_kind k, const double p[3])
{
    bool inside;
    switch (k) {
    case WORLD_SOLIDS: return solids(p);
    case WORLD_FRACTAL: /* outside the bounding sphere its distance, as the shader's map() (the estimate is no bound far out) */
        return camera_norm(p) > BULB_BOUND + 0.1 ? camera_norm(p) - BULB_BOUND : bulb(p, &inside) * BULB_STEP;
    case WORLD_TERRAIN: return (p[1] - terrain_height(p[0], p[2])) / sqrt(1 + TERRAIN_SLOPE * TERRAIN_SLOPE);
    case WORLD_PLANE: return p[1];
    }
    return 0;
}

static bool world_inside(world_kind k, const double p[3])
{
    bool inside = false;
    if (k == WORLD_FRACTAL)
        bulb(p, &inside);
    else
        inside = world(k, p) <= 0;
    return inside;
}

/* The renderer's probe: the distance at the float-rounded point, as a float (the GPU's numbers). */
static void probe(void *ctx, const double *pts, int n, float *out)
{
    world_kind k = *(const world_kind *)ctx;
    for (int i = 0; i < n; i++) {
        double q[3] = {(float)pts[3 * i], (float)pts[3 * i + 1], (float)pts[3 * i + 2]};
        out[i] = (float)world(k, q);
    }
}

static double frand(unsigned *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

/* 1,000 random flights of 200 frames per world, half the steps aimed at the solids, with steps at
 * every scale from 1e-6 of the world's size to 50 times it (the way Shift and a scroll-wheel can ask): no
 * flight ever ends a frame inside a solid or crosses one between frames (checked along both legs of
 * each step's path at CHECKS points each with the exact inside test). */
static void slide_never_enters_a_solid(void **st)
{
    enum { CHECKS = 250 };
    (void)st;
    const world_kind kinds[] = {WORLD_SOLIDS, WORLD_FRACTAL, WORLD_TERRAIN};
    const double size[] = {6, 1.5, 6};
    for (int w = 0; w < 3; w++) {
        world_kind k = kinds[w];
        unsigned seed = 42;
        int crossings = 0, steps = 0;
        double closest = INFINITY, kept = 0;
        for (int f = 0; f < 1000; f++) {
            double pos[3];
            do {
                for (int i = 0; i < 3; i++)
                    pos[i] = (2 * frand(&seed) - 1) * size[w];
            } while (world(k, pos) <= 0.01 * size[w]);
            for (int s = 0; s < 200; s++) {
                /* log-uniform lengths from 1e-6 to 50 sizes, half of them aimed at the solids near the origin */
                double from[3] = {pos[0], pos[1], pos[2]}, to[3], dir[3];
                double len = size[w] * pow(10, -6 + 7.7 * frand(&seed)), aim = frand(&seed) < 0.5 ? 1 : 0;
                for (int i = 0; i < 3; i++)
                    dir[i] = (2 * frand(&seed) - 1) - aim * from[i] / fmax(camera_norm(from), 1e-9);
                double dl = fmax(camera_norm(dir), 1e-9);
                for (int i = 0; i < 3; i++)
                    to[i] = from[i] + len * dir[i] / dl;
                double corner[3];
                kept += camera_slide(from, to, 1.0f, camera_resolution(from, false), probe, &k, corner);
                for (int j = 1; j <= 2 * CHECKS; j++) { /* the path: from → corner → to */
                    double q[3], u = (j % CHECKS) / (double)CHECKS;
                    const double *a = j <= CHECKS ? from : corner, *b = j <= CHECKS ? corner : to;
                    for (int i = 0; i < 3; i++)
                        q[i] = a[i] + (b[i] - a[i]) * (j % CHECKS == 0 ? 1.0 : u);
                    if (world_inside(k, q)) {
                        fprintf(stderr, "  entered at %d/(2 x CHECKS) of a %.3g step from %.9g %.9g %.9g (bound there %.3g)\n", j,
                                len, from[0], from[1], from[2], world(k, from));
                        crossings++;
                        break;
                    }
                }
                closest = fmin(closest, world(k, to));
                memcpy(pos, to, sizeof pos);
                steps++;
            }
        }
        fprintf(stderr, "  world %d: %d steps in 1000 flights: %d entered a solid; closest approach %.3g; mean kept %.3f\n",
                w, steps, crossings, closest, kept / steps);
        assert_int_equal(crossings, 0);
        assert_true(closest > 0);
    }
}

/* Sliding: a step never stalls near a surface. 10 µm above the plane y = 0, a step of 5 cm that leaves
 * it at 45° keeps ≥ 90 % of its length (the two-ball rule kept 6e-5 of it); one along the surface at
 * the skin's clearance keeps all of it; one into the surface at 30° keeps its part along the surface
 * and stops at the skin; and after that, backing away is free. */
static void slide_never_stalls(void **st)
{
    (void)st;
    world_kind k = WORLD_PLANE;
    const double L = 0.05, res = 1e-9;
    for (int a = 1; a < 36; a++) { /* away from the surface at 5° … 85° off it */
        double ang = a * 2.5 * GLM_PI / 180, from[3] = {0.3, 1e-5, -0.2};
        double to[3] = {from[0] + L * cos(ang), from[1] + L * sin(ang), from[2]};
        float kept = camera_slide(from, to, 1.0f, res, probe, &k, NULL);
        if (kept < 0.9f)
            fprintf(stderr, "  at %.1f degrees: kept %.4f\n", ang * 180 / GLM_PI, (double)kept);
        if (fabs(ang - GLM_PI / 4) < 1e-9)
            fprintf(stderr, "  10 um from a plane, a 5 cm step at 45 degrees off it keeps %.4f\n", (double)kept);
        assert_true(kept >= 0.9f);
    }
    /* along the surface at the skin's clearance: all of it */
    double from[3] = {0, CAMERA_SKIN * L, 0}, to[3] = {L, CAMERA_SKIN * L, 0};
    assert_true(camera_slide(from, to, 1.0f, res, probe, &k, NULL) >= 0.999f);
    /* into it at 30° from 1 m: the part along it is kept, the height stops at the skin */
    double hi[3] = {0, 1, 0}, in[3] = {2 * cos(GLM_PI / 6), 1 - 2 * sin(GLM_PI / 6), 0};
    camera_slide(hi, in, 1.0f, res, probe, &k, NULL);
    assert_true(fabs(in[0] - 2 * cos(GLM_PI / 6)) < 1e-6 && fabs(in[1] - CAMERA_SKIN * 2) < 1e-6);
    /* stuck at 4 µm in front of a wall (the glass sphere's case): straight back and sideways move */
    double near[3] = {0, 4e-6, 0}, back[3] = {0, 0.067, 0}, side[3] = {0.067, 4e-6, 0};
    assert_true(camera_slide(near, back, 1.0f, res, probe, &k, NULL) >= 0.999f);
    double near2[3] = {0, 4e-6, 0};
    float sideways = camera_slide(near2, side, 1.0f, res, probe, &k, NULL);
    fprintf(stderr, "  4 um from a plane, a 6.7 cm step along it keeps %.2g (the skin: %.2g m)\n", (double)sideways,
            CAMERA_SKIN * 0.067);
    /* inside (or unknown) the move is free, so a camera can get out; far away is clamped to the range */
    double a[3] = {0, -0.5, 0}, b[3] = {5, -0.5, 0};
    assert_true(camera_slide(a, b, 1.0f, res, probe, &k, NULL) == 1.0f && b[0] == 5.0);
    double far[3] = {1e9, 0, 0}, centre[3] = {1, 0, 0};
    camera_clamp_range(far, centre, 100);
    assert_true(fabs(far[0] - 101.0) < 1e-9);
}

/* The pivot's direction in the camera's own frame (right, up, forward), unit. */
/* Movement by real time: S held for 4 s moves the camera as far at 2 fps (frames of 0.5 s) as at
 * 30 fps, through open space and gliding 5 cm above the terrain world's floor (where one 0.5 s step
 * would lift out by its skin, an eighth of its length, and be held back); and per_distance speed
 * (a fractal's) the same. A frame of 10 s moves CAMERA_MAX_STEPS steps only. */
static void travel_is_by_real_time(void **st)
{
    (void)st;
    world_kind k = WORLD_TERRAIN;
    struct { double y; bool per_distance; } cases[] = {{3.0, false}, {0.0, false}, {3.0, true}};
    for (int c = 0; c < 3; c++) {
        double end[2][3];
        for (int run = 0; run < 2; run++) {
            float dt = run ? 0.5f : 1.0f / 30.0f;
            int frames = run ? 8 : 120;
            double start[3] = {-2.0, cases[c].y, 0.0};
            if (cases[c].y == 0.0) { /* 5 cm above the ground below the start */
                start[1] = 10.0;
                float d;
                probe(&k, start, 1, &d);
                start[1] -= d - 0.05;
            }
            double at[3] = {start[0] + 1, start[1], start[2]};
            camera cam = camera_look_at(start, at, 1.0f);
            camera_input in = {.move = {0, 0, -1}};
            camera_travel_rule r = {.speed = cases[c].per_distance ? 0.1f : 0.5f, .sensitivity = 0.0025f,
                                    .per_distance = cases[c].per_distance, .min_distance = 1e-6f, .step_factor = 1.0f};
            for (int f = 0; f < frames; f++)
                camera_travel(&cam, &in, dt, &r, probe, &k);
            memcpy(end[run], cam.position, sizeof end[run]);
        }
        double moved = fabs(end[0][0] + 2.0), gap = camera_distance(end[0], end[1]);
        fprintf(stderr, "  case %d: 4 s at 30 fps moved %.4g m; at 2 fps %.4g m from there\n", c, moved, gap);
        assert_true(moved > 0.1);
        assert_true(gap < 1e-4 * moved);
    }
    double start[3] = {0, 3, 0}, at[3] = {1, 3, 0};
    camera cam = camera_look_at(start, at, 1.0f);
    camera_input in = {.move = {0, 0, 1}};
    camera_travel_rule r = {.speed = 1.0f, .sensitivity = 0.0025f, .step_factor = 1.0f};
    assert_int_equal(camera_travel(&cam, &in, 10.0f, &r, probe, &k), CAMERA_MAX_STEPS);
    assert_true(fabs(camera_distance(cam.position, start) - CAMERA_MAX_STEPS * (double)CAMERA_STEP_S) < 1e-3);
}

static void seen(const camera *c, const double pivot[3], double out[3])
{
    camera_basis b = camera_get_basis(c);
    double d[3] = {pivot[0] - c->position[0], pivot[1] - c->position[1], pivot[2] - c->position[2]}, len = camera_norm(d);
    out[0] = (d[0] * b.right[0] + d[1] * b.right[1] + d[2] * b.right[2]) / len;
    out[1] = (d[0] * b.up[0] + d[1] * b.up[1] + d[2] * b.up[2]) / len;
    out[2] = (d[0] * b.forward[0] + d[1] * b.forward[1] + d[2] * b.forward[2]) / len;
}

/* Orbiting turns the camera about a pivot off the screen's centre (the point a drag started on): the
 * pivot stays where it is on the screen and at the same distance; pitch stops short of straight down. */
static void orbit_keeps_the_pivot(void **st)
{
    (void)st;
    camera c = camera_look_at((double[3]){1, 2, 5}, (double[3]){0, 0.5, 0}, 0.9f);
    const double pivot[3] = {0.4, 0.2, -0.3}; /* not where the camera looks */
    double before[3], after[3], r0 = camera_distance(c.position, pivot);
    seen(&c, pivot, before);
    for (int i = 0; i < 50; i++) {
        camera_orbit(&c, pivot, 0.07f, (float)(i % 3 - 1) * 0.05f);
        seen(&c, pivot, after);
        for (int k = 0; k < 3; k++)
            assert_near(after[k], before[k], 1e-5);
        assert_near(camera_distance(c.position, pivot), r0, 1e-9 * r0);
    }
    for (int i = 0; i < 100; i++)
        camera_orbit(&c, pivot, 0, -0.1f);
    assert_true(c.pitch >= -CAMERA_MAX_PITCH);
}

/* A deep zoom's camera keeps a double's digits: a step of 1e-13 at |p| = 1 moves it (a float cannot). */
static void deep_positions(void **st)
{
    (void)st;
    camera c = camera_look_at((double[3]){1, 0, 0}, (double[3]){1, 0, -1}, 1.0f);
    camera_input fwd = {.move = {0, 0, 1}};
    camera_update(&c, &fwd, 1.0f, 1e-13f, 0.0f);
    assert_true(c.position[2] < 0 && fabs(c.position[2] + 1e-13) < 1e-20);
    assert_false(camera_degenerate((double[3]){1, 0, 0}, (double[3]){1, 0, 1e-13}));
    assert_true(camera_degenerate((double[3]){1, 0, 0}, (double[3]){1 + 2.2e-16, 0, 0}));
    assert_true(camera_resolution((double[3]){1, 0, 0}, true) < 1e-14);
    assert_true(camera_resolution((double[3]){1, 0, 0}, false) > 1e-7);
}

/* Roll turns right toward up; camera_set_basis inverts camera_get_basis for every orientation,
 * straight up and down included; look_at_up puts the image's top toward the given up. */
static void roll_and_free_orientation(void **st)
{
    (void)st;
    camera c = {.roll = (float)(GLM_PI / 2)};
    camera_basis b = camera_get_basis(&c);
    assert_near(b.right[1], 1.0, TOL); /* right is now the world's up */
    assert_near(b.up[0], -1.0, TOL);
    assert_near(b.forward[2], -1.0, TOL);
    for (int i = 0; i < 300; i++) {
        camera a = {.yaw = (float)i * 0.37f - 3.0f, .pitch = ((float)(i % 41) / 20.0f - 1.0f) * 1.5707963f,
                    .roll = (float)(i % 29) * 0.21f - 3.0f};
        camera_basis ba = camera_get_basis(&a);
        camera r = {0};
        camera_set_basis(&r, ba.forward, ba.up);
        camera_basis br = camera_get_basis(&r);
        for (int k = 0; k < 3; k++) {
            assert_near(br.forward[k], ba.forward[k], 1e-5);
            assert_near(br.right[k], ba.right[k], 1e-5);
            assert_near(br.up[k], ba.up[k], 1e-5);
        }
    }
    /* a Z-up camera looking straight down: pitch −90° exactly, the image's top toward −Z */
    camera d = camera_look_at_up((double[3]){0, 5, 0}, (double[3]){0, 0, 0}, (double[3]){0, 0, -1}, 1.0f);
    b = camera_get_basis(&d);
    assert_near(b.forward[1], -1.0, TOL);
    assert_near(b.up[2], -1.0, TOL);
    assert_near(b.right[0], 1.0, TOL);
    /* a level look with up tilted 30° to the right: roll −30° (the camera turned clockwise) */
    camera t = camera_look_at_up((double[3]){0, 0, 0}, (double[3]){0, 0, -1}, (double[3]){sin(GLM_PI / 6), cos(GLM_PI / 6), 0}, 1.0f);
    assert_near(t.roll, -GLM_PI / 6, TOL);
    assert_near(t.pitch, 0.0, TOL);
}

/* Free flight turns about the camera's own axes: a roll then a yaw of 90° each turns toward what was
 * the camera's up; the frame stays orthonormal over many small turns. */
static void free_turns(void **st)
{
    (void)st;
    camera c = {0};
    camera_turn(&c, 0, 0, (float)(GLM_PI / 2)); /* right → world up */
    camera_turn(&c, (float)(GLM_PI / 2), 0, 0); /* yaw left about the camera's up (world −X) */
    camera_basis b = camera_get_basis(&c);
    /* yawing left about up = −X from forward −Z: forward turns toward −right = −Y */
    assert_near(b.forward[1], -1.0, 1e-5);
    camera_input in = {.look = {3, -2}, .roll = 0.5f, .free = true};
    for (int i = 0; i < 1000; i++)
        camera_update(&c, &in, 0.01f, 0, 0.01f);
    b = camera_get_basis(&c);
    assert_near(glm_vec3_norm(b.forward), 1.0, 1e-5);
    assert_near(glm_vec3_dot(b.forward, b.up), 0.0, 1e-5);
    assert_near(glm_vec3_dot(b.right, b.up), 0.0, 1e-5);
    /* the level camera keeps its roll while it looks around, and its pitch limit */
    camera l = {.roll = 0.3f};
    camera_input look = {.look = {50, 1e6f}};
    camera_update(&l, &look, 0.0f, 1.0f, 0.01f);
    assert_near(l.roll, 0.3, TOL);
    assert_near(l.pitch, -CAMERA_MAX_PITCH, TOL);
}

/* camera_ray_from: the projections' closed forms (camera.h), an eye per half with stereo, nothing
 * outside a fisheye's circle; the pixel angle per projection. */
static void projections_rays(void **st)
{
    (void)st;
    camera c = camera_look_at((double[3]){0, 0, 0}, (double[3]){0, 0, -1}, (float)(GLM_PI / 3));
    double o[3];
    vec3 d;
    c.lens.projection = PROJECTION_EQUIRECTANGULAR;
    assert_true(camera_ray_from(&c, 400, 200, 299.5f, 99.5f, o, d)); /* λ = 90°, φ = 0: +X */
    assert_near(d[0], 1.0, 1e-5);
    assert_near(camera_pixel_angle(&c, 200), GLM_PI / 200, TOL);
    c.lens.projection = PROJECTION_FISHEYE;
    assert_false(camera_ray_from(&c, 100, 100, 0, 0, o, d)); /* a corner: outside the circle */
    assert_true(camera_ray_from(&c, 100, 100, 99, 49.5f, o, d)); /* the right edge: 90° × 0.99 off the axis */
    assert_near(d[0], sin(0.99 * GLM_PI / 2), 1e-5);
    assert_near(camera_pixel_angle(&c, 100), GLM_PI / 100, TOL); /* 180° across the circle's 100 pixels */
    c.lens = (camera_lens){.projection = PROJECTION_ORTHOGRAPHIC, .focus = 4};
    assert_true(camera_ray_from(&c, 100, 50, 99.5f, 24.5f, o, d)); /* the right edge's centre */
    assert_near(d[2], -1.0, TOL);
    assert_near(o[0], 4 * tan(GLM_PI / 6) * 2, 1e-5); /* focus · tan(fov/2) · aspect */
    assert_near(camera_footprint_t0(&c), 4.0, TOL);
    c.lens = (camera_lens){.stereo = STEREO_SIDE_BY_SIDE, .eye_separation = 0.2f, .focus = 5};
    camera_ray_from(&c, 200, 100, 49.5f, 49.5f, o, d); /* the left eye's centre aims at the focal point */
    assert_near(o[0], -0.1, 1e-6);
    assert_near(d[0] / -d[2], 0.1 / 5, 1e-5);
    camera_ray_from(&c, 200, 100, 149.5f, 49.5f, o, d);
    assert_near(o[0], 0.1, 1e-6);
    int ew, eh;
    c.lens.stereo = STEREO_TOP_BOTTOM;
    camera_eye_size(&c, 200, 100, &ew, &eh);
    assert_int_equal(ew, 200);
    assert_int_equal(eh, 50);
    assert_near(camera_pixel_angle(&c, 100), 2 * tan(GLM_PI / 6) / 50, TOL);
}

/* Which eye is where (issue 58 items 14 and 17: the top-bottom eyes swapped and omnidirectional stereo's offset
 * sign survived the tests; the docs said ODS converges at the focus). Top-bottom: the top half is the left eye.
 * Omnidirectional: a pixel's two rays are parallel whatever the focus (they converge at infinity), from eyes
 * ∓sep/2 along the ray's own right: looking ahead (−Z) the left eye is at −X, looking east (+X) at −Z. */
static void stereo_eyes_and_convergence(void **st)
{
    (void)st;
    camera c = camera_look_at((double[3]){0, 0, 0}, (double[3]){0, 0, -1}, (float)(GLM_PI / 3));
    double o[3], o2[3];
    vec3 d, d2;
    c.lens = (camera_lens){.stereo = STEREO_TOP_BOTTOM, .eye_separation = 0.2f, .focus = 5};
    camera_ray_from(&c, 200, 200, 99.5f, 149.5f, o, d); /* GL rows count up: 149.5 is the top half */
    assert_near(o[0], -0.1, 1e-6);
    camera_ray_from(&c, 200, 200, 99.5f, 49.5f, o, d);
    assert_near(o[0], 0.1, 1e-6);
    c.lens = (camera_lens){.projection = PROJECTION_EQUIRECTANGULAR, .stereo = STEREO_SIDE_BY_SIDE,
                           .eye_separation = 0.2f, .focus = 5};
    const float xs[2] = {199.5f, 299.5f}; /* per eye of 400: λ = 0 (ahead) and λ = 90° (east) */
    for (int k = 0; k < 2; k++) {
        camera_ray_from(&c, 800, 200, xs[k], 99.5f, o, d);
        camera_ray_from(&c, 800, 200, xs[k] + 400, 99.5f, o2, d2);
        for (int i = 0; i < 3; i++)
            assert_near(d[i], d2[i], 1e-6); /* parallel: no disparity at infinity, none made at the focus */
        assert_near(k == 0 ? o[0] : o[2], -0.1, 1e-6);
        assert_near(k == 0 ? o2[0] : o2[2], 0.1, 1e-6);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(look_at_points_forward),
        cmocka_unit_test(default_orientation),
        cmocka_unit_test(basis_is_orthonormal_and_level),
        cmocka_unit_test(rays_span_the_field_of_view),
        cmocka_unit_test(moving_and_turning),
        cmocka_unit_test(roll_and_free_orientation),
        cmocka_unit_test(free_turns),
        cmocka_unit_test(projections_rays),
        cmocka_unit_test(stereo_eyes_and_convergence),
        cmocka_unit_test(slide_never_enters_a_solid),
        cmocka_unit_test(slide_never_stalls),
        cmocka_unit_test(deep_positions),
        cmocka_unit_test(travel_is_by_real_time),
        cmocka_unit_test(orbit_keeps_the_pivot),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
