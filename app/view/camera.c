#include "view/camera.h"

#include <float.h>

#include <math.h>

static float clampf(float v, float lo, float hi) { return v < lo ? lo : v > hi ? hi : v; }

camera camera_look_at(const vec3 eye, const vec3 target, float fov_y)
{
    camera c = {.fov_y = fov_y};
    glm_vec3_copy((float *)eye, c.position);
    vec3 d;
    glm_vec3_sub((float *)target, (float *)eye, d);
    float len = glm_vec3_norm(d);
    if (len > 0) {
        glm_vec3_scale(d, 1.0f / len, d);
        c.yaw = atan2f(-d[0], -d[2]);
        c.pitch = clampf(asinf(clampf(d[1], -1, 1)), -CAMERA_MAX_PITCH, CAMERA_MAX_PITCH);
    }
    return c;
}

bool camera_degenerate(const vec3 eye, const vec3 target)
{
    float d = glm_vec3_distance((float *)eye, (float *)target);
    return !(d > 1e-6f * (1.0f + glm_vec3_norm((float *)eye)));
}

camera camera_look_at_deg(const vec3 eye, const vec3 target, float fov_y_deg)
{
    return camera_look_at(eye, target, glm_rad(fov_y_deg));
}

camera_basis camera_get_basis(const camera *c)
{
    camera_basis b;
    float cp = cosf(c->pitch), sp = sinf(c->pitch), cy = cosf(c->yaw), sy = sinf(c->yaw);
    b.forward[0] = -sy * cp;
    b.forward[1] = sp;
    b.forward[2] = -cy * cp;
    /* right = forward × world-up, normalized: stays horizontal so the horizon never rolls */
    b.right[0] = cy;
    b.right[1] = 0;
    b.right[2] = -sy;
    glm_vec3_cross(b.right, b.forward, b.up);
    return b;
}

void camera_update(camera *c, const camera_input *in, float dt, float speed, float sensitivity)
{
    static const float FAST_FACTOR = 4.0f;
    c->yaw -= in->look[0] * sensitivity;
    c->pitch = clampf(c->pitch - in->look[1] * sensitivity, -CAMERA_MAX_PITCH, CAMERA_MAX_PITCH);
    c->yaw = remainderf(c->yaw, 2.0f * GLM_PIf);
    camera_basis b = camera_get_basis(c);
    float step = speed * dt * (in->fast ? FAST_FACTOR : 1.0f);
    vec3 world_up = {0, 1, 0};
    glm_vec3_muladds(b.right, in->move[0] * step, c->position);
    glm_vec3_muladds(world_up, in->move[1] * step, c->position);
    glm_vec3_muladds(b.forward, in->move[2] * step, c->position);
}

float camera_clamp_step(const vec3 from, vec3 to, float free_from, float free_to)
{
    if (!(free_from > 0))
        return 1.0f;
    /* float resolution of the position, with room: a step that ends closer could round into a surface */
    float margin = 8.0f * FLT_EPSILON * (1.0f + glm_vec3_norm((float *)from) + glm_vec3_norm(to));
    float len = glm_vec3_distance((float *)from, to);
    if (free_to > margin && len <= free_from + free_to - margin)
        return 1.0f;
    float limit = fmaxf(CAMERA_SAFE_FRACTION * free_from - margin, 0.0f);
    if (len <= limit)
        return 1.0f;
    float keep = limit / len;
    for (int i = 0; i < 3; i++)
        to[i] = from[i] + (to[i] - from[i]) * keep;
    return keep;
}

void camera_clamp_range(vec3 pos, const vec3 centre, float max_distance)
{
    float d = glm_vec3_distance(pos, (float *)centre);
    if (d > max_distance)
        for (int i = 0; i < 3; i++)
            pos[i] = centre[i] + (pos[i] - centre[i]) * (max_distance / d);
}

void camera_ray(const camera *c, int width, int height, float x, float y, vec3 dir)
{
    camera_basis b = camera_get_basis(c);
    float t = tanf(0.5f * c->fov_y);
    float sx = (2.0f * (x + 0.5f) / (float)width - 1.0f) * t * (float)width / (float)height;
    float sy = (2.0f * (y + 0.5f) / (float)height - 1.0f) * t;
    for (int i = 0; i < 3; i++)
        dir[i] = b.forward[i] + sx * b.right[i] + sy * b.up[i];
    glm_vec3_normalize(dir);
}

float camera_pixel_angle(const camera *c, int height) { return 2.0f * tanf(0.5f * c->fov_y) / (float)height; }
