/* geo_fixture — the DEM the GIS tests share and the coordinate helpers they check with (geo_fixture.h). */
#include "geo_fixture.h"

char fixture_dir[] = "/tmp/fathom-geo-XXXXXX";
const double DEM_GT[6] = {400000, 1000, 0, 5300000, 0, -1000}; /* UTM 33N, 1 km texels */

const char *fixture_path(const char *name)
{
    static char full[16][256];
    static int k;
    k = (k + 1) % 16;
    snprintf(full[k], sizeof full[k], "%s/%s", fixture_dir, name);
    return full[k];
}

double fixture_hill(int i, int j) { return 300 + 250 * sin(0.2 * i) * cos(0.15 * j) + 4 * i; }

OGRSpatialReferenceH fixture_srs(int epsg)
{
    OGRSpatialReferenceH s = OSRNewSpatialReference(NULL);
    OSRImportFromEPSG(s, epsg);
    OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
    return s;
}

int fixture_setup(void **st)
{
    (void)st;
    if (!mkdtemp(fixture_dir))
        return -1;
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), fixture_path("dem.tif"), W, H, 1, GDT_Float32, NULL);
    GDALSetGeoTransform(ds, (double *)DEM_GT);
    OGRSpatialReferenceH s = fixture_srs(32633);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    float v[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            v[j * W + i] = (float)fixture_hill(i, j);
    int ok = GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, W, H, v, W, H, GDT_Float32, 0, 0) == CE_None;
    GDALClose(ds);
    return ok ? 0 : -1;
}

int fixture_teardown(void **st)
{
    (void)st;
    return remove_tree(fixture_dir);
}

/* UTM 33N x, y to longitude and latitude, by OSR here. */
void fixture_utm_to_lonlat(double x, double y, double *lon, double *lat)
{
    OGRSpatialReferenceH u = fixture_srs(32633), g = fixture_srs(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(u, g);
    double z = 0;
    assert_true(OCTTransform(t, 1, &x, &y, &z));
    *lon = x, *lat = y;
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(u);
    OSRDestroySpatialReference(g);
}
