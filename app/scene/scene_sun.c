/* scene_sun — the "sun" block: a directional light placed by a date, a local hour and a place
 * (data/sky/sun.h: NOAA's solar position), its colour the direct beam's through the air. The place is the
 * DEM's centre (data/geo/geo.h) unless the block gives latitude and longitude. The hour is a number so a
 * flight's "set" track can run a day ("sun.hour": 6 → 20) and the panel shows it as a slider. */
#define _XOPEN_SOURCE 700 /* M_PI is XSI */
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "data/geo/dem.h"
#include "data/geo/geo.h"
#include "data/sky/sky.h"
#include "data/sky/sun.h"
#include "scene/scene_parse.h"

bool scene_parse_sun(scene_ctx *c, const cJSON *root)
{
    struct scene_sun *sun = &c->s->sun;
    const cJSON *b = cJSON_GetObjectItemCaseSensitive(root, "sun");
    if (!b)
        return true;
    static const char *const keys[] = {"date", "hour", "utc_offset", "latitude", "longitude", "light", NULL};
    if (!cJSON_IsObject(b))
        return scene_fail(c, "sun", "expected an object: {\"date\": \"2026-06-21\", \"hour\": 18.5, \"utc_offset\": 5.75}");
    const char *date = NULL;
    float lat = NAN, lon = NAN; /* read only when given: the panel shows no slider for "the DEM's centre" */
    bool place = cJSON_HasObjectItem(b, "latitude") || cJSON_HasObjectItem(b, "longitude");
    if (!scene_check_keys(c, b, "sun", keys) || !scene_get_str(c, b, "sun", "date", NULL, &date) ||
        !scene_get_num(c, b, "sun", "hour", 12, 0, 24, &sun->hour) ||
        !scene_get_num(c, b, "sun", "utc_offset", 0, -14, 14, &sun->utc_offset) ||
        (place && !scene_get_num(c, b, "sun", "latitude", NAN, -90, 90, &lat)) ||
        (place && !scene_get_num(c, b, "sun", "longitude", NAN, -180, 180, &lon)) ||
        !scene_get_int(c, b, "sun", "light", 0, 0, SCENE_MAX_LIGHTS - 1, &sun->light))
        return false;
    double t;
    if (!date || strlen(date) >= sizeof sun->date || !sun_time(date, sun->hour, sun->utc_offset, &t))
        return scene_fail(c, "sun.date", "expected a date \"YYYY-MM-DD\" that exists (e.g. \"2026-06-21\")");
    if (isnan(lat) != isnan(lon))
        return scene_fail(c, isnan(lat) ? "sun.latitude" : "sun.longitude", "give both latitude and longitude, or "
                                                                            "neither (the DEM's centre)");
    snprintf(sun->date, sizeof sun->date, "%s", date);
    sun->latitude = lat, sun->longitude = lon;
    sun->on = true;
    return true;
}

/* The DEM's centre in longitude and latitude. */
static bool dem_centre(const scene *s, double *lon, double *lat, err_t *err)
{
    int w, h;
    double range[2];
    dem_info info;
    if (!s->terrain.heightmap[0] || !dem_probe(s->terrain.heightmap, &w, &h, range, &info, err) || !info.georeferenced)
        return err_set(err, "sun: the scene has no georeferenced DEM to place the sun over: give sun.latitude and "
                            "sun.longitude");
    double col = (w - 1) / 2.0, row = (h - 1) / 2.0;
    return geo_convert(s->terrain.heightmap, false, 1, &col, &row, lon, lat, err);
}

bool scene_apply_sun(scene *s, err_t *err)
{
    struct scene_sun *sun = &s->sun;
    if (!sun->on)
        return true;
    if (sun->light >= s->light_count || s->lights[sun->light].type != LIGHT_DIRECTIONAL)
        return err_set(err, "%s: sun.light %d is not a directional light of the scene's (it has %d lights): the "
                            "sun moves a directional light", s->path, sun->light, s->light_count);
    double lon, lat;
    err_t none;
    bool on_dem = dem_centre(s, &lon, &lat, isnan(sun->latitude) ? err : &none);
    if (isnan(sun->latitude) && !on_dem)
        return false;
    if (isnan(sun->latitude))
        sun->longitude = lon, sun->latitude = lat;
    /* the terrain's −Z is its grid's north: on a projected DEM true north is turned from it (by up to 45° on a
     * polar stereographic one), measured at the DEM's centre */
    sun->convergence = 0;
    if (on_dem && !geo_true_north(s->terrain.heightmap, lon, lat, &sun->convergence, err))
        return false;
    double t;
    sun_time(sun->date, sun->hour, sun->utc_offset, &t);
    sun_position p = sun_at(t, sun->latitude, sun->longitude);
    sun->azimuth = p.azimuth, sun->elevation = p.elevation;
    scene_light *l = &s->lights[sun->light];
    double az = (p.azimuth + sun->convergence) * M_PI / 180, el = p.elevation * M_PI / 180;
    /* east is +X, grid north −Z (data/geo/terrain.h) */
    l->vec[0] = (float)(cos(el) * sin(az));
    l->vec[1] = (float)sin(el);
    l->vec[2] = (float)(-cos(el) * cos(az));
    if (s->has_sky) /* the physical sky colours the beam with its own air (scene_apply_sky) */
        return true;
    float beam[3];
    sun_color(p.elevation, beam);
    for (int k = 0; k < 3; k++)
        l->color[k] *= beam[k];
    return true;
}

bool scene_apply_sky(scene *s, err_t *err)
{
    if (!s->has_sky && !(s->effects & (1u << EFFECT_SKY))) /* compiled out, the lights still see the air */
        return true;
    int li = s->sun.on ? s->sun.light : -1;
    for (int i = 0; li < 0 && i < s->light_count; i++)
        if (s->lights[i].type == LIGHT_DIRECTIONAL)
            li = i;
    bool lit = li >= 0 && s->lights[li].type == LIGHT_DIRECTIONAL;
    if (!lit && s->has_sky)
        return err_set(err, "%s: environment.sky \"physical\" needs a directional light for the sun (add one to "
                            "\"lights\", or a \"sun\" block)", s->path);
    /* only forced in (effects.sky=on: the bench pricing it) and no directional light: a sun 45° up,
     * irradiance 3 */
    scene_light fallback = {.type = LIGHT_DIRECTIONAL, .vec = {0.5f, 0.7071f, 0.5f}, .color = {1, 1, 1}, .intensity = 3};
    scene_light *l = lit ? &s->lights[li] : &fallback;
    struct scene_sky *k = &s->sky;
    double sun[3] = {l->vec[0], l->vec[1], l->vec[2]}, ms[SKY_MS_N][3];
    k->scale = s->terrain.heightmap[0] && s->terrain.exaggeration > 0 ? s->terrain.exaggeration : 1;
    /* the light and the ambient as they are where the camera looks (a terrain's heights are exaggerated) */
    double altitude = fmax(s->cam_look_at[1] / k->scale, 0), T[3], mean[3];
    sky_multiple_scattering(sun, ms);
    sky_transmittance(altitude, sun, -1, 64, T);
    sky_mean(altitude, sun, (const double(*)[3])ms, mean);
    for (int c = 0; c < 3; c++) {
        k->sun[c] = (float)sun[c];
        k->irradiance[c] = l->color[c] * l->intensity;
        for (int i = 0; i < SKY_MS_N; i++)
            k->ms[i][c] = (float)ms[i][c];
        if (s->has_sky) { /* a forced-in sky leaves the scene's own lights and environment alone */
            s->env_color[c] = (float)(mean[c] * k->irradiance[c]);
            l->color[c] = (float)(l->color[c] * T[c]);
        }
    }
    if (s->has_sky)
        s->env_intensity = 1;
    return true;
}
