/* cli_gis — `fathom viewshed`, `fathom track` and `fathom water`'s options (cli_gis.h). */
#include "cli/cli_gis.h"

#include "cli/cli.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char USAGE_GIS[] =
    "       fathom viewshed --dem DEM --observer LON,LAT --output VIEW.tif [--observer-height M]\n"
    "                       [--target-height M] [--refraction K] [--flat-earth] [--radius M]\n"
    "       fathom track --dem DEM --input TRACK.gpx|.kml|.geojson|.gpkg|.shp --output FLIGHT.json\n"
    "                    [--height M] [--speed M/S]\n"
    "       fathom track --dem DEM --path FLIGHT.json --output TRACK.gpx|.kml [--fps N] [--scene S]\n"
    "  viewshed: what an observer (LON,LAT in WGS 84 degrees, M metres above the ground [1.7]) sees of\n"
    "  the DEM, exactly (every line of sight against the bilinear surface), with Earth curvature and\n"
    "  refraction K [0.13]; a GeoTIFF on the DEM's grid: 1 visible, 0 hidden, 255 nodata or beyond\n"
    "  --radius (docs/guide/gis.md). track: a GPS track becomes a flight M metres above the ground\n"
    "  [100] (its times, or --speed [30 m/s]); a flight becomes a GPX track or a KML tour.\n"
    "       fathom water --dem DEM --output LAKES.tif [--min-depth M] [--min-area M2]\n"
    "  water: the lakes the DEM implies, its depressions filled to their spill heights (priority-flood);\n"
    "  lakes shallower than M metres or smaller than M2 square metres stay dry; a GeoTIFF on the DEM's\n"
    "  grid: band 1 the water surface's height (nodata where dry; terrain.water=LAKES.tif draws it),\n"
    "  band 2 the depth (0 dry).\n";

const char *cli_gis_usage(void) { return USAGE_GIS; }

static const char *command_name(gis_command c)
{
    return c == GIS_VIEWSHED ? "viewshed" : c == GIS_WATER ? "water" : "track";
}

static bool number(const char *name, const char *val, double lo, double hi, double *out, err_t *err)
{
    double v = 0;
    if (!util_parse_decimal(val, &v) || !(v >= lo && v <= hi))
        return err_set(err, "bad %s '%s': expected a number from %g to %g", name, val, lo, hi);
    *out = v;
    return true;
}

static bool option(const char *name, const char *val, gis_options *o, err_t *err)
{
    static const struct { const char *name; size_t at; } FILES[] = {
        {"--dem", offsetof(gis_options, dem)},     {"--output", offsetof(gis_options, output)},
        {"--input", offsetof(gis_options, input)}, {"--path", offsetof(gis_options, path)},
        {"--scene", offsetof(gis_options, scene)}};
    for (size_t k = 0; k < sizeof FILES / sizeof FILES[0]; k++)
        if (!strcmp(name, FILES[k].name)) {
            *(const char **)((char *)o + FILES[k].at) = val;
            return true;
        }
    if (!strcmp(name, "--set")) {
        if (o->set_count == (int)(sizeof o->sets / sizeof o->sets[0]))
            return err_set(err, "too many --set (at most %d)", (int)(sizeof o->sets / sizeof o->sets[0]));
        o->sets[o->set_count++] = val;
        return true;
    }
    if (!strcmp(name, "--observer")) {
        int used = 0;
        if (sscanf(val, "%lf,%lf%n", &o->lon, &o->lat, &used) != 2 || val[used] || !(fabs(o->lon) <= 180) ||
            !(fabs(o->lat) <= 90))
            return err_set(err, "bad --observer '%s': expected LON,LAT in degrees (WGS 84), e.g. 86.925,27.988", val);
        return true;
    }
    static const struct { const char *name; size_t at; double lo, hi; } NUMBERS[] = {
        {"--observer-height", offsetof(gis_options, observer_height), 0, 1e5},
        {"--target-height", offsetof(gis_options, target_height), 0, 1e5},
        {"--refraction", offsetof(gis_options, refraction), -1, 1},
        {"--radius", offsetof(gis_options, radius), 1, 2e7},
        {"--height", offsetof(gis_options, height), 0, 1e5},
        {"--speed", offsetof(gis_options, speed), 0.01, 1e5},
        {"--fps", offsetof(gis_options, fps), 0.01, 1000},
        {"--min-depth", offsetof(gis_options, min_depth), 0, 1e5},
        {"--min-area", offsetof(gis_options, min_area), 0, 1e15}};
    for (size_t k = 0; k < sizeof NUMBERS / sizeof NUMBERS[0]; k++)
        if (!strcmp(name, NUMBERS[k].name))
            return number(name, val, NUMBERS[k].lo, NUMBERS[k].hi, (double *)((char *)o + NUMBERS[k].at), err);
    return err_set(err, "unknown option '%s' for fathom %s (see fathom --help)", name, command_name(o->command));
}

static bool ends_with(const char *s, const char *ext)
{
    size_t n = strlen(s), e = strlen(ext);
    return n > e && !strcasecmp(s + n - e, ext);
}

static bool check(const gis_options *o, err_t *err)
{
    const char *cmd = command_name(o->command);
    if (!o->dem || !o->output)
        return err_set(err, "fathom %s needs --dem DEM and --output FILE (see fathom --help)", cmd);
    if ((o->min_depth > 0 || o->min_area > 0) && o->command != GIS_WATER)
        return err_set(err, "--min-depth and --min-area belong to fathom water");
    if (o->command == GIS_WATER) {
        if (!isnan(o->lon) || o->input || o->path || o->scene || o->set_count)
            return err_set(err, "fathom water takes --dem, --output, --min-depth and --min-area (see fathom --help)");
        if (!ends_with(o->output, ".tif") && !ends_with(o->output, ".tiff"))
            return err_set(err, "bad --output '%s': the lakes are a GeoTIFF: end the name in .tif", o->output);
        return true;
    }
    if (o->command == GIS_VIEWSHED) {
        if (isnan(o->lon))
            return err_set(err, "fathom viewshed needs --observer LON,LAT: where the observer stands");
        if (o->input || o->path || o->scene || o->set_count)
            return err_set(err, "--input, --path, --scene and --set belong to fathom track");
        if (!ends_with(o->output, ".tif") && !ends_with(o->output, ".tiff"))
            return err_set(err, "bad --output '%s': the viewshed is a GeoTIFF: end the name in .tif", o->output);
        return true;
    }
    if (!isnan(o->lon))
        return err_set(err, "--observer belongs to fathom viewshed");
    if (!o->input == !o->path)
        return err_set(err, "fathom track takes either --input TRACK (a GPS track to a flight) or --path FLIGHT.json "
                            "(a flight to a GPS track)");
    if (o->input && !ends_with(o->output, ".json"))
        return err_set(err, "bad --output '%s': a track becomes a flight: end the name in .json", o->output);
    if (o->path && !ends_with(o->output, ".gpx") && !ends_with(o->output, ".kml"))
        return err_set(err, "bad --output '%s': a flight becomes a GPS track: end the name in .gpx or .kml", o->output);
    return true;
}

bool cli_gis_parse(int argc, char **argv, gis_options *o, err_t *err)
{
    *o = (gis_options){.lon = NAN, .lat = NAN, .observer_height = 1.7, .refraction = 0.13, .height = 100,
                       .speed = 30, .fps = 2};
    if (argc < 2 || (strcmp(argv[1], "viewshed") && strcmp(argv[1], "track") && strcmp(argv[1], "water")))
        return true;
    o->command = !strcmp(argv[1], "viewshed") ? GIS_VIEWSHED : !strcmp(argv[1], "water") ? GIS_WATER : GIS_TRACK;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--quiet")) {
            o->quiet = true;
            continue;
        }
        if (!strcmp(a, "--flat-earth")) {
            o->flat_earth = true;
            continue;
        }
        char name[32];
        const char *eq = strchr(a, '='), *val;
        if (!strncmp(a, "--", 2) && eq && (size_t)(eq - a) < sizeof name) {
            memcpy(name, a, (size_t)(eq - a));
            name[eq - a] = '\0';
            val = eq + 1;
        } else if (strlen(a) < sizeof name && !strncmp(a, "--", 2)) {
            strcpy(name, a);
            if (i + 1 == argc)
                return err_set(err, "option %s needs a value (see fathom --help)", name);
            val = argv[++i];
        } else {
            return err_set(err, "unexpected '%s' (see fathom --help)", a);
        }
        for (int k = 2; k < i - (eq ? 0 : 1); k++) /* an option given twice: which one counts is a guess */
            if (strcmp(name, "--set") && !strncmp(argv[k], name, strlen(name)) &&
                (argv[k][strlen(name)] == '\0' || argv[k][strlen(name)] == '='))
                return err_set(err, "%s is given twice (the second time '%s'): give it once", name, val);
        if (!option(name, val, o, err))
            return false;
    }
    return check(o, err);
}
