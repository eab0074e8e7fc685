/* gis_job — `fathom viewshed` and `fathom track` (cli_gis.h; docs/guide/gis.md).
 *
 * viewshed: the DEM read whole (data/geo/dem.h), the observer placed by its longitude and latitude
 * (data/geo/geo.h), every texel's line of sight decided exactly (data/geo/viewshed.h), the answer written as
 * a GeoTIFF on the DEM's grid, and a line saying what share is visible and what it took.
 *
 * track: a GPS track (GPX, KML, GeoJSON, GeoPackage, Shapefile) becomes a flight file (view/path.h)
 * over the DEM's scene, `height` metres above the ground under each point (the heights exaggerated as
 * the scene draws them), looking ahead along the track; keys at least a texel apart, times from the
 * track's own or its length at `speed`. A flight becomes a GPX track (positions, altitudes above the
 * sea, times from the flight's start at 2000-01-01 UTC unless the file ...) or a KML with a gx:Tour whose cameras
 * look where the flight looks. */
#ifndef FATHOM_GIS_JOB_H
#define FATHOM_GIS_JOB_H

#include <stdbool.h>

#include "cli/cli_gis.h"
#include "util.h"

bool gis_viewshed_run(const gis_options *o, err_t *err);
bool gis_track_run(const gis_options *o, err_t *err);
/* `fathom water`: the DEM read whole, its lakes filled (data/geo/water.h), surface and depth written as a
 * GeoTIFF on its grid (the surface band 1: terrain.water draws it), and a line: lakes, area, volume, deepest. */
bool gis_water_run(const gis_options *o, err_t *err);

#endif
