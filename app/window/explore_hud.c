/* explore_hud — the text over the image (explore_app.h): one line, all of it (F2), or nothing (F3). */
#include "window/explore_app.h"

#include <stdio.h>

#include "gpu/res_heightfield.h"
#include "window/hud.h"

/* The converged image's rays that found no answer: said, never hidden (they are drawn as misses). */
const char *explore_unresolved_text(const explore_app *a)
{
    static char text[160];
    snprintf(text, sizeof text, "%ld px ran out of steps (drawn as misses): H shows them magenta; raise quality.max_steps",
             a->unresolved);
    return text;
}

/* The full HUD's lines about the camera and the knobs the window steps (only those the scene uses). */
static void hud_details(const explore_app *a, int h, strbuf *t)
{
    const camera *c = &a->fly.cam;
    const scene *s = &a->s.scene;
    flycam_describe(&a->fly, s, t);
    sb_printf(t, "pos %.10g %.10g %.10g  fov %.1f  roll %.1f%s\n", c->position[0], c->position[1], c->position[2],
              (double)glm_deg(c->fov_y), (double)glm_deg(c->roll), a->fly.level ? " (level)" : " (free flight: U levels)");
    if (c->lens.projection || c->lens.stereo || c->lens.aperture > 0)
        sb_printf(t, "%s%s%s  lens %.3g, focus %.4g (F: under the cursor)\n", CAMERA_PROJECTIONS[c->lens.projection],
                  c->lens.stereo ? ", stereo " : "", c->lens.stereo ? CAMERA_STEREOS[c->lens.stereo] : "",
                  (double)c->lens.aperture, (double)c->lens.focus);
    float d = a->fly.surface_distance, pa = camera_pixel_angle(c, h);
    double floor = s->fractal.deep_now ? camera_resolution(c->position, true)
                                       : (double)PRECISION_REL * (camera_norm(c->position) + (double)d);
    if (s->adaptive_speed && (double)(s->quality.hit_k * d * pa) < floor)
        sb_printf(t, "%s precision reached: detail below %.2g m cannot be resolved here\n",
                  s->fractal.deep_now ? "double" : "float", floor);
    else if (s->fractal.deep_now)
        sb_printf(t, "double precision (deep zoom)\n");
    for (int k = 0; k < KNOB_COUNT; k++)
        if (knob_window_steps((knob_id)k) && scene_knob_applies(s, (knob_id)k))
            sb_printf(t, "%s%s %g%s  ", k == (int)a->knob ? "[" : "", knob_get_def((knob_id)k)->name,
                      knob_value(&s->quality, (knob_id)k), k == (int)a->knob ? "]" : "");
    sb_printf(t, "\nWASD move  mouse look  Space/C up/down  Shift fast  scroll speed  O orbit%s\n"
                 "F1 panel  Enter type an edit  F2 this help  F3 hide  1-%d scenes  K knob  =/- step  H steps  G grab  V difference\n"
                 "Home start  B save view  Ctrl+1-9 recall  J fragment preset  Ctrl+Z undo  Ctrl+S preset  N keyframe (%d)  L play  "
                 "R reload  P shot  Esc quit\n",
              s->terrain.heightmap[0] ? "  T walk" : "", a->scene_count, a->flight.key_count);
}

void explore_hud(const explore_app *a, int w, int h)
{
    if (a->hud == HUD_HIDDEN)
        return;
    const scene *s = &a->s.scene;
    double ms = framestats_average_ms(&a->stats);
    int iw, ih;
    render_active_size(&iw, &ih);
    strbuf t = {0};
    static const char *const views[] = {"", "  [steps]", "  [difference to the grabbed frame]"};
    sb_printf(&t, "%s  %s  %dx%d%s  %.0f ms/sample  %d/%d spp  %s%s  F1 panel  F2 help\n", s->name,
              preset_name(s->preset), iw, ih, views[a->view], a->cost.sample_ms, render_samples(), s->quality.spp,
              flycam_mode_name(&a->fly), s->fractal.deep_now ? "  double" : "");
    if (a->hud == HUD_FULL) {
        sb_printf(&t, "%.1f ms a frame (%.1f fps)\n", ms, ms > 0 ? 1000.0 / ms : 0.0);
        hud_details(a, h, &t);
    }
    if (a->unresolved > 0)
        sb_printf(&t, "%s\n", explore_unresolved_text(a));
    if (res_heightfield_streamed()) { /* what is resident, and what the image still draws as plateaus */
        res_heightfield_stats st = res_heightfield_get_stats();
        sb_printf(&t, "terrain streamed: %d of %d tiles resident (%d slots), %d pending%s\n", st.resident, st.tiles,
                  st.slots, st.pending, st.pending ? ": plateaus where they go" : "");
    }
    if (a->cursor_info[0])
        sb_printf(&t, "%s\n", a->cursor_info);
    if (a->message[0] && !a->panel)
        sb_printf(&t, "%s\n", a->message);
    float scale = h >= 900 ? 2.0f : 1.5f;
    hud_draw(t.data, 0, 0, w, h, scale);
    sb_free(&t);
    if (a->view == VIEW_STEPS) { /* the legend's labels over the bar display.frag draws */
        char legend[160];
        snprintf(legend, sizeof legend, "primary-ray steps a pixel: 0 (blue) ... %.0f (red); magenta: unresolved (out of steps)",
                 (double)render_heat_max());
        hud_draw(legend, 16, -34, w, h, scale);
    }
}

