/* cli_gis — the GIS commands' options (docs/guide/gis.md):
 *   fathom viewshed --dem DEM --observer LON,LAT --output VIEW.tif [...]   (jobs/gis/gis_job.h)
 *   fathom track --dem DEM --input TRACK.gpx --output FLIGHT.json [...]    a GPS track to a flight
 *   fathom track --dem DEM --path FLIGHT.json --output TRACK.gpx|.kml      a flight to a GPS track
 *   fathom water --dem DEM --output LAKES.tif [--min-depth M] [--min-area M2]  the lakes a DEM implies */
#ifndef FATHOM_CLI_GIS_H
#define FATHOM_CLI_GIS_H

#include <stdbool.h>

#include "util.h"

typedef enum gis_command { GIS_NONE, GIS_VIEWSHED, GIS_TRACK, GIS_WATER } gis_command;

typedef struct gis_options {
    gis_command command;
    const char *dem, *output, *input, *path, *scene;
    const char *sets[64];
    int set_count;
    double lon, lat;        /* --observer */
    double observer_height; /* --observer-height M [1.7] */
    double target_height;   /* --target-height M [0] */
    double refraction;      /* --refraction K [0.13] */
    bool flat_earth;        /* --flat-earth: no curvature at all */
    double radius;          /* --radius M [0: the whole DEM] */
    double height;          /* track: --height M above the ground [100] */
    double speed;           /* track: --speed M/S when the track has no times [30] */
    double fps;             /* track --path: samples a second [2] */
    double min_depth;       /* water: --min-depth M, lakes shallower stay dry [0] */
    double min_area;        /* water: --min-area M2, lakes smaller stay dry [0] */
    bool quiet;
} gis_options;

/* GIS_NONE in o->command when argv[1] is not a GIS command (then nothing else is touched). */
bool cli_gis_parse(int argc, char **argv, gis_options *o, err_t *err);

#endif
