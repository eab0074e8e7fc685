/* geo_fixture — the GeoTIFF the GIS tests share, written once in a temporary folder by their fixture_setup, and the coordinate helpers they check with */
#ifndef FATHOM_TEST_GEO_FIXTURE_H
#define FATHOM_TEST_GEO_FIXTURE_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "check.h"
#include "data/geo/dem.h"
#include "data/geo/geo.h"
#include "data/sky/sun.h"
#include "data/geo/viewshed.h"
#include "data/geo/water.h"
#include "jobs/gis/gis_job.h"
#include "scene/scene.h"
#include "view/path.h"

extern char fixture_dir[]; /* the temporary folder: fixture_path(NAME) is a file in it */
enum { W = 64, H = 48 };
extern const double DEM_GT[6];

const char *fixture_path(const char *name);

double fixture_hill(int i, int j);

OGRSpatialReferenceH fixture_srs(int epsg);

int fixture_setup(void **st);

int fixture_teardown(void **st);

/* UTM 33N x, y to longitude and latitude, by OSR here. */
void fixture_utm_to_lonlat(double x, double y, double *lon, double *lat);

#endif
