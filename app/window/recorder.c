/* recorder — the window's recorded flight (recorder.h). */
#include "window/recorder.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/route.h"
#include "view/views.h"

void recorder_free(recorder *r)
{
    path_free(&r->flight);
    r->key_count = 0;
    r->trail_count = 0;
    r->playing = false;
}

static path_camera key_of(const camera *c)
{
    path_camera k = {.yaw = c->yaw, .pitch = c->pitch, .roll = c->roll, .fov_deg = glm_deg(c->fov_y)};
    memcpy(k.position, c->position, sizeof k.position);
    return k;
}

void recorder_follow(recorder *r, const camera *c)
{
    if (r->key_count == 0 || r->playing)
        return;
    const double *last = r->trail_count ? r->trail[r->trail_count - 1].position : r->keys[r->key_count - 1].position;
    if (!memcmp(last, c->position, sizeof c->position))
        return;
    if (r->trail_count == RECORDER_TRAIL_MAX) { /* full: every other point, the way's shape kept */
        for (int i = 0; i < RECORDER_TRAIL_MAX / 2; i++)
            r->trail[i] = r->trail[2 * i + 1];
        r->trail_count = RECORDER_TRAIL_MAX / 2;
    }
    r->trail[r->trail_count++] = key_of(c);
}

void recorder_load(recorder *r, const char *scene_name, char *message, size_t n)
{
    char file[PATH_MAX_LEN];
    err_t e;
    recorder_free(r);
    message[0] = '\0';
    if (!views_flight_file(scene_name, file, sizeof file, &e) || !util_file_exists(file))
        return;
    if (!path_load(file, &r->flight, &e)) {
        snprintf(message, n, "the recorded flight is unreadable (%.1500s); N starts a new one", e.msg);
        return;
    }
    for (int i = 0; i < r->flight.count && i < RECORDER_MAX_KEYS; i++)
        path_key_camera(&r->flight, i, &r->keys[r->key_count++]);
}

void recorder_clear(recorder *r, const char *scene_name, char *message, size_t n)
{
    char file[PATH_MAX_LEN];
    err_t e;
    recorder_free(r);
    if (!views_flight_file(scene_name, file, sizeof file, &e)) {
        snprintf(message, n, "%s", e.msg);
        return;
    }
    remove(file);
    snprintf(message, n, "flight cleared (%s removed)", file);
}

void recorder_add(recorder *r, const char *scene_name, const camera *c, double speed, camera_probe_fn probe,
                  void *ctx, char *message, size_t n)
{
    char file[PATH_MAX_LEN];
    err_t e;
    r->playing = false;
    if (!views_flight_file(scene_name, file, sizeof file, &e)) {
        snprintf(message, n, "%s", e.msg);
        return;
    }
    if (r->key_count == RECORDER_MAX_KEYS) {
        snprintf(message, n, "the flight has %d keys already", RECORDER_MAX_KEYS);
        return;
    }
    path_camera *k = &r->keys[r->key_count];
    *k = key_of(c);
    k->time = path_next_key_time(r->keys, r->key_count, c->position, speed);
    r->key_count++;
    if (r->key_count < 2) {
        r->trail_count = 0;
        snprintf(message, n, "keyframe 1 at t = 0 s: fly on and press N again");
        return;
    }
    int added = route_clear(r->keys, &r->key_count, RECORDER_MAX_KEYS, r->trail, r->trail_count, speed, probe, ctx);
    if (added < 0) { /* the trail is kept: a key further on may still route around */
        snprintf(message, n, "keyframe not added: the spline to here would pass through a surface, and the way you "
                             "flew has no keys that clear it; add a key where you turned (N), then this one");
        return;
    }
    r->trail_count = 0;
    strbuf text = {0};
    path_text_from_cameras(r->keys, r->key_count, &text);
    path_free(&r->flight);
    bool ok = path_parse(text.data, file, &r->flight, &e) && util_write_text_atomic(file, text.data, "the flight", &e);
    sb_free(&text);
    if (ok)
        snprintf(message, n, "keyframe %d at t = %.1f s%s, saved to %s (L plays; render it with fathom render --path)",
                 r->key_count, r->keys[r->key_count - 1].time,
                 added ? " (and keys along the way you flew, so the spline stays clear of the scene)" : "", file);
    else
        snprintf(message, n, "%s", e.msg);
}

void recorder_toggle_play(recorder *r, char *message, size_t n)
{
    if (r->flight.count < 2) {
        snprintf(message, n, "no flight to play: N records keyframes");
        return;
    }
    r->playing = !r->playing;
    r->play_t = r->flight.keys[0].time;
    snprintf(message, n, r->playing ? "playing the flight (L stops)" : "stopped");
}

bool recorder_play(recorder *r, double dt, camera *c, char *message, size_t n)
{
    if (!r->playing)
        return false;
    r->play_t += dt;
    path_sample smp;
    path_eval(&r->flight, r->play_t, &smp);
    memcpy(c->position, smp.position, sizeof c->position);
    c->yaw = (float)smp.yaw;
    c->pitch = (float)smp.pitch;
    c->roll = (float)smp.roll;
    c->fov_y = glm_rad((float)smp.fov_deg);
    if (r->play_t >= r->flight.keys[r->flight.count - 1].time) {
        r->playing = false;
        snprintf(message, n, "flight played: %.1f s, %d keys", path_duration(&r->flight), r->flight.count);
    }
    return true;
}
