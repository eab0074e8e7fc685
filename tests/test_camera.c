/* Camera maths against double-precision expectations. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "check.h"

#include "camera.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(look_at_points_forward),
        cmocka_unit_test(default_orientation),
        cmocka_unit_test(basis_is_orthonormal_and_level),
        cmocka_unit_test(rays_span_the_field_of_view),
        cmocka_unit_test(moving_and_turning),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
