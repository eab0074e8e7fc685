/* Camera maths against double-precision expectations. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#include "check.h"

#include "view/camera.h"

static const double TOL = 2e-6;

static void look_at_points_forward(void **st)
{
    (void)st;
    const float targets[][3] = {{0, 0, -1}, {3, 1, 2}, {-5, -2, 0.5f}, {0.1f, 7, 0}};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        vec3 eye = {1, 2, 3};
        camera c = camera_look_at(eye, targets[i], 1.0f);
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
    camera c = camera_look_at((vec3){0, 0, 0}, (vec3){0, 0, -1}, (float)fov);
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
    camera c = camera_look_at((vec3){0, 1, 0}, (vec3){0, 1, -1}, 1.0f);
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

/* Exact distance to a field of spheres and boxes (double): the safe-flight test's world. */
static double world(const double p[3])
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

static double frand(unsigned *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

/* 1,000 random flights of 200 frames with huge random steps (up to 50 m a frame, the way Shift and a
 * scroll-wheel can ask), in float as the window flies: no flight ever ends a frame inside a solid or
 * crosses one between frames (checked along each step at 1,000 points). */
static void safe_flight_never_enters_a_solid(void **st)
{
    (void)st;
    unsigned seed = 42;
    int crossings = 0, steps = 0;
    double closest = INFINITY;
    for (int f = 0; f < 1000; f++) {
        vec3 pos;
        double p[3];
        do {
            for (int i = 0; i < 3; i++)
                pos[i] = (float)(12 * frand(&seed) - 6), p[i] = pos[i];
        } while (world(p) <= 0.05);
        for (int k = 0; k < 200; k++) {
            vec3 from, to;
            glm_vec3_copy(pos, from);
            double len = 50 * pow(frand(&seed), 3);
            for (int i = 0; i < 3; i++)
                to[i] = from[i] + (float)(len * (2 * frand(&seed) - 1));
            double here[3] = {from[0], from[1], from[2]}, there[3] = {to[0], to[1], to[2]};
            camera_clamp_step(from, to, (float)world(here), (float)world(there));
            for (int j = 1; j <= 1000; j++) {
                double q[3];
                for (int i = 0; i < 3; i++)
                    q[i] = (double)from[i] + ((double)to[i] - (double)from[i]) * (double)j / 1000.0;
                if (world(q) <= 0) {
                    crossings++;
                    break;
                }
            }
            double end[3] = {to[0], to[1], to[2]};
            closest = fmin(closest, world(end));
            glm_vec3_copy(to, pos);
            steps++;
        }
    }
    fprintf(stderr, "  %d steps in 1000 flights: %d entered a solid; closest approach %.3g m\n", steps, crossings,
            closest);
    assert_int_equal(crossings, 0);
    assert_true(closest > 0);
    /* inside (or unknown) the move is free, so a camera can get out; far away is clamped to the range */
    vec3 a = {0, 0, 0}, b = {5, 0, 0};
    assert_true(camera_clamp_step(a, b, -0.5f, 1.0f) == 1.0f && b[0] == 5.0f);
    /* at 1e-5 from a surface (the plane y = 0) and moving straight away from it: allowed */
    vec3 c = {0, 1e-5f, 0}, d = {0, 2, 0};
    assert_true(camera_clamp_step(c, d, 1e-5f, 2.0f) == 1.0f);
    /* a step past a thin wall, both ends free by 0.1: refused, shortened to 0.9 of the free ball */
    vec3 e = {0, 0, 0}, g = {1, 0, 0};
    assert_true(fabsf(camera_clamp_step(e, g, 0.1f, 0.1f) - 0.09f) < 1e-4f);
    vec3 far = {1e9f, 0, 0}, centre = {1, 0, 0};
    camera_clamp_range(far, centre, 100);
    assert_true(fabsf(far[0] - 101.0f) < 1e-3f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(look_at_points_forward),
        cmocka_unit_test(default_orientation),
        cmocka_unit_test(basis_is_orthonormal_and_level),
        cmocka_unit_test(rays_span_the_field_of_view),
        cmocka_unit_test(moving_and_turning),
        cmocka_unit_test(safe_flight_never_enters_a_solid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
