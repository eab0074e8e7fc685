/* GIS on the GPU. The physical sky (shaders/common/sky.glsl) against its double-precision twin
 * (data/sky/sky.h) pixel by pixel, and aerial perspective dimming a hit as the twin's transmittance says.
 * Imagery on the rendered terrain (gpu/res_imagery.c, shaders/terrain/layers.glsl): a UTM DEM draped
 * with an image whose western half is red and eastern half blue, and whose northern half has green, in
 * another CRS (WGS 84), split at a known longitude and latitude: every pixel whose hit (the position AOV) lies more than a texel from that meridian
 * has its half's albedo (pure within 6 km of the camera, dominant beyond, where the mipmaps of a
 * distant view blend the halves; hits seen at grazing angles, whose footprint spans the map, left
 * out); opacity 0 draws the terrain exactly as without imagery; and only a scene with
 * imagery compiles its sampler. Two layers composite in order. */
#define _XOPEN_SOURCE 700 /* mkdtemp */
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
#include <gdal.h>
#include <ogr_srs_api.h>

#include "check.h"
#include "gltest.h"
#include "data/sky/sky.h"
#include "gpu/render.h"
#include "gpu/res_heightfield.h"

static char dir[] = "/tmp/fathom-drape-XXXXXX";
enum { DW = 48, DH = 40 };                  /* DEM texels, 200 m each, UTM 33N */
static const double GT[6] = {500000, 200, 0, 5200000, 0, -200};
static double split_lon;                    /* the meridian between red and blue (green: north of the centre) */

static OGRSpatialReferenceH srs_of(int epsg)
{
    OGRSpatialReferenceH s = OSRNewSpatialReference(NULL);
    OSRImportFromEPSG(s, epsg);
    OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
    return s;
}

static void write_raster(const char *name, int w, int h, int bands, const double gt[6], int epsg, const void *px,
                         GDALDataType type)
{
    char file[256];
    snprintf(file, sizeof file, "%s/%s", dir, name);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, w, h, bands, type, NULL);
    GDALSetGeoTransform(ds, (double *)gt);
    OGRSpatialReferenceH s = srs_of(epsg);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    int size = GDALGetDataTypeSizeBytes(type);
    for (int b = 0; b < bands; b++)
        assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Write, 0, 0, w, h,
                                      (char *)px + (size_t)b * (size_t)w * (size_t)h * (size_t)size, w, h, type, 0, 0),
                         CE_None);
    GDALClose(ds);
}

static int setup(void **st)
{
    if (!mkdtemp(dir))
        return -1;
    GDALAllRegister();
    float hts[DW * DH];
    for (int j = 0; j < DH; j++)
        for (int i = 0; i < DW; i++)
            hts[j * DW + i] = (float)(400 + 120 * sin(0.2 * i) * cos(0.25 * j));
    write_raster("dem.tif", DW, DH, 1, GT, 32633, hts, GDT_Float32);
    /* the DEM's centre meridian, and a WGS 84 image 0.3° × 0.2° around it: red west, blue east */
    OGRSpatialReferenceH u = srs_of(32633), g = srs_of(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(u, g);
    double x = GT[0] + DW * 100.0, y = GT[3] - DH * 100.0, z = 0;
    OCTTransform(t, 1, &x, &y, &z);
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(u);
    OSRDestroySpatialReference(g);
    enum { IW = 300, IH = 200 };
    const double px = 0.001, gt[6] = {round(x * 1000) / 1000 - 0.15, px, 0, y + 0.1, 0, -px};
    split_lon = gt[0] + 150 * px;
    static unsigned char img[3 * IW * IH], grey[3 * IW * IH];
    for (int j = 0; j < IH; j++)
        for (int i = 0; i < IW; i++) {
            img[j * IW + i] = i < 150 ? 255 : 0;                /* red band */
            img[IW * IH + j * IW + i] = j < 100 ? 255 : 0;     /* green: the northern half */
            img[2 * IW * IH + j * IW + i] = i < 150 ? 0 : 255; /* blue band */
            for (int c = 0; c < 3; c++)
                grey[c * IW * IH + j * IW + i] = 128;
        }
    write_raster("halves.tif", IW, IH, 3, gt, 4326, img, GDT_Byte);
    write_raster("grey.tif", IW, IH, 3, gt, 4326, grey, GDT_Byte);
    return gl_setup(st);
}

static int teardown(void **st)
{
    return remove_tree(dir) | gl_teardown(st);
}

static void render_with(const char *imagery, float *aov, float *rgba, scene *s)
{
    char text[1024];
    snprintf(text, sizeof text,
             "{\"program\": \"terrain\", \"materials\": {\"rock\": {\"base_color\": [0.5, 0.5, 0.5]}},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0.3, 1, 0.2]}],"
             " \"quality\": {\"max_dist\": 1e6, \"spp\": 1}, \"effects\": {\"textures\": \"off\"},"
             " \"terrain\": {\"heightmap\": \"%s/dem.tif\"%s%s}}",
             dir, imagery ? ", \"imagery\": " : "", imagery ? imagery : "");
    load_text(text, NULL, 0, s);
    camera cam = cam_at(-3000, 4000, 3500, 0, 300, 0, 55);
    draw(s, &cam, W, H, 1, NULL, aov, rgba);
}

static void halves_land_on_their_sides(void **st)
{
    (void)st;
    static float aov[W * H * AOV], rgba[W * H * 4];
    scene s;
    char layer[320];
    snprintf(layer, sizeof layer, "\"%s/halves.tif\"", dir);
    render_with(layer, aov, rgba, &s);
    strbuf pre = {0};
    scene_preamble(&s, &pre);
    assert_non_null(strstr(pre.data, "#define TERRAIN_IMAGERY 1"));
    sb_free(&pre);
    scene_free(&s);
    /* the split meridian's x at the DEM's centre row, in world metres: x = easting − the DEM's middle */
    OGRSpatialReferenceH u = srs_of(32633), g = srs_of(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(g, u);
    int red = 0, blue = 0, wrong = 0;
    for (int k = 0; k < W * H; k++) {
        const float *a = aov + (size_t)k * AOV;
        if (!isfinite(a[AOV_SLOT_DEPTH]))
            continue;
        double wx = a[AOV_SLOT_POSITION], wz = a[AOV_SLOT_POSITION + 2], z = 0;
        double n = GT[3] - (wz + DH * 100.0); /* world z to northing: row 0 is the DEM's north edge */
        /* the meridian's easting at this northing, between two of its points (straight to < 1 m here) */
        double e1 = split_lon, n1 = 46.8, e2 = split_lon, n2 = 47.0;
        OCTTransform(t, 1, &e1, &n1, &z);
        OCTTransform(t, 1, &e2, &n2, &z);
        double e = e1 + (e2 - e1) * (n - n1) / (n2 - n1);
        double metres = (wx + GT[0] + DW * 100.0) - e; /* + east of the split */
        if (fabs(metres) < 200)
            continue; /* within a texel of the meridian: the blend */
        if (fabs(wx) > DW * 100.0 - 500 || fabs(wz) > DH * 100.0 - 500)
            continue; /* the outer two texels: the footprint's normal there (central differences reaching
                       * past the edge) tilts, and its mip level jumps (noted in issue 41's closing note) */
        const float *alb = a + AOV_SLOT_ALBEDO;
        /* near the camera each pixel's footprint is a few texels: the colour is its half's, pure; far
         * away, at grazing angles, the mipmaps blend in the other half (as any texture's): it must still
         * dominate */
        double v[3] = {wx + 3000, a[AOV_SLOT_POSITION + 1] - 4000, wz - 3500}; /* from the camera */
        double dist = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        const float *nn = a + AOV_SLOT_NORMAL;
        if (fabs(v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2]) < 0.25 * dist)
            continue; /* grazing: one pixel's footprint spans the map (the top mip level) */
        float pure = dist < 6000 ? 0.1f : 0.45f;
        bool is_red = alb[0] > 0.5f && alb[2] < pure, is_blue = alb[2] > 0.5f && alb[0] < pure;
        red += metres < 0 && is_red;
        blue += metres > 0 && is_blue;
        bool bad = metres < 0 ? !is_red : !is_blue;
        double north = n - (GT[3] - DH * 100.0); /* from the split parallel (the DEM's central one: its
                                                  * centre sits on the central meridian, no convergence) */
        if (fabs(north) > 200)
            bad = bad || (north > 0 ? alb[1] < 0.5f : alb[1] > pure);
        if (bad && wrong < 8)
            print_message("wrong: x %.1f z %.1f y %.1f, %.1f m from the split, albedo %.3f %.3f %.3f\n", wx, wz,
                          a[AOV_SLOT_POSITION + 1], metres, alb[0], alb[1], alb[2]);
        wrong += bad;
    }
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(u);
    OSRDestroySpatialReference(g);
    print_message("drape on the surface: %d red and %d blue hits on their sides, %d wrong\n", red, blue, wrong);
    assert_int_equal(wrong, 0);
    assert_true(red > 300 && blue > 300);
}

static void opacity_zero_is_no_imagery(void **st)
{
    (void)st;
    static float plain[W * H * 4], clear[W * H * 4], over[W * H * AOV];
    scene s;
    render_with(NULL, NULL, plain, &s);
    strbuf pre = {0};
    scene_preamble(&s, &pre);
    assert_null(strstr(pre.data, "TERRAIN_IMAGERY")); /* only what the scene uses is compiled */
    sb_free(&pre);
    scene_free(&s);
    char layer[400];
    snprintf(layer, sizeof layer, "{\"file\": \"%s/halves.tif\", \"opacity\": 0}", dir);
    render_with(layer, NULL, clear, &s);
    scene_free(&s);
    assert_memory_equal(plain, clear, sizeof plain);
    /* two layers: grey at half opacity over the halves gives their mean with grey */
    snprintf(layer, sizeof layer, "[\"%s/halves.tif\", {\"file\": \"%s/grey.tif\", \"opacity\": 0.5}]", dir, dir);
    render_with(layer, over, NULL, &s);
    scene_free(&s);
    int mixed = 0;
    for (int k = 0; k < W * H; k++) {
        const float *alb = over + (size_t)k * AOV + AOV_SLOT_ALBEDO;
        if (!isfinite(over[(size_t)k * AOV + AOV_SLOT_DEPTH]) || alb[1] <= 0)
            continue;
        /* sRGB 128 over 255 or 0 at ½: bytes 191.5 or 64, decoded to linear: green is grey's alone (64) */
        mixed += fabsf(alb[1] - 0.0513f) < 0.01f; /* sRGB 64/255 = 0.0513 linear */
    }
    print_message("two layers: %d hits with grey's half in green\n", mixed);
    assert_true(mixed > 600);
}

/* The sky seen from 2 km up, looking 25° above the horizon: each sky pixel's radiance against
 * data/sky/sky.h's march with 256 steps (the shader takes 16 and 8), the sun's disc left out. */
static void sky_matches_its_twin(void **st)
{
    (void)st;
    static float aov[W * H * AOV], rgba[W * H * 4];
    char text[1024];
    snprintf(text, sizeof text,
             "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"environment\": {\"sky\": \"physical\"},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0.5, 0.35, -1], \"intensity\": 3,"
             " \"color\": [1, 0.9, 0.8]}], \"quality\": {\"max_dist\": 1e6, \"spp\": 1},"
             " \"terrain\": {\"heightmap\": \"%s/dem.tif\", \"exaggeration\": 1}}", dir);
    scene s;
    load_text(text, NULL, 0, &s);
    strbuf pre = {0};
    scene_preamble(&s, &pre);
    assert_non_null(strstr(pre.data, "#define FX_SKY 1"));
    sb_free(&pre);
    camera cam = cam_at(0, 2000, 6000, 0, 2000 + 4000 * tan(25 * DEG2RAD), 2000, 70);
    draw(&s, &cam, W, H, 1, NULL, aov, rgba);
    double sun[3] = {s.sky.sun[0], s.sky.sun[1], s.sky.sun[2]}, ms[SKY_MS_N][3];
    for (int i = 0; i < SKY_MS_N; i++)
        for (int k = 0; k < 3; k++)
            ms[i][k] = s.sky.ms[i][k];
    double worst = 0, sum = 0;
    int n = 0;
    for (int row = 0; row < H; row += 3)
        for (int x = 0; x < W; x += 3) {
            size_t k = (size_t)(row * W + x);
            if (isfinite(aov[k * AOV + AOV_SLOT_DEPTH]))
                continue; /* terrain */
            dray r = pixel_ray(&cam, x, row, W, H);
            if (r.d[0] * sun[0] + r.d[1] * sun[1] + r.d[2] * sun[2] > cos(2 * DEG2RAD))
                continue; /* the disc */
            double L[3], T[3];
            sky_radiance(2000, r.d, -1, sun, (const double(*)[3])ms, 256, L, T);
            for (int c = 0; c < 3; c++) {
                double want = L[c] * s.sky.irradiance[c], got = rgba[k * 4 + (size_t)c];
                worst = fmax(worst, fabs(got / want - 1));
                sum += fabs(got / want - 1);
                n++;
            }
        }
    print_message("sky: %d channels of sky pixels, mean %.2f %%, worst %.2f %% off the double-precision march\n", n,
                  100 * sum / n, 100 * worst);
    assert_true(n > 300);
    assert_true(sum / n < 0.02 && worst < 0.05);
    /* aerial perspective: the terrain (heights ×2) from 1 km up, glowing a constant 0.5 and reflecting nothing
     * (black metal), with the sky compiled out and in: each hit's light is 0.5 times the air's
     * transmittance plus its in-scattering */
    static float off[W * H * 4], on[W * H * 4];
    camera down = cam_at(0, 2000, 4000, 0, 400, -2000, 60);
    const char *glow[] = {"materials.rock.base_color=0,0,0", "materials.rock.metallic=1", "materials.rock.roughness=1",
                          "materials.rock.emission=0.5,0.5,0.5", "terrain.exaggeration=2", "effects.sky=off"};
    scene s_off, s_on;
    load_text(text, glow, 6, &s_off);
    draw(&s_off, &down, W, H, 1, NULL, aov, off);
    scene_free(&s_off);
    load_text(text, glow, 5, &s_on); /* heights ×2: the air is measured in metres, 1 km below the eye's 2 km */
    draw(&s_on, &down, W, H, 1, NULL, NULL, on);
    scene_free(&s_on);
    double aworst = 0;
    int hits = 0;
    for (int k = 0; k < W * H; k++) {
        const float *a = aov + (size_t)k * AOV;
        if (!isfinite(a[AOV_SLOT_DEPTH]))
            continue;
        double dx = a[AOV_SLOT_POSITION] - down.position[0], dy = (a[AOV_SLOT_POSITION + 1] - down.position[1]) / 2,
               dz = a[AOV_SLOT_POSITION + 2] - down.position[2], L[3], T[3];
        double len = sqrt(dx * dx + dy * dy + dz * dz), d[3] = {dx / len, dy / len, dz / len};
        sky_radiance(1000, d, len, sun, (const double(*)[3])ms, 256, L, T);
        for (int c = 0; c < 3; c++) {
            double want = off[(size_t)k * 4 + (size_t)c] * T[c] + L[c] * s.sky.irradiance[c];
            if (off[(size_t)k * 4 + (size_t)c] < 0.5f || off[(size_t)k * 4 + (size_t)c] > 0.7f) /* the glow, a glint of the sun */
                fail_msg("hit %d: %.6f without the sky, not the glow (0.5)", k, off[(size_t)k * 4 + (size_t)c]);
            aworst = fmax(aworst, fabs(on[(size_t)k * 4 + (size_t)c] / want - 1));
        }
        hits++;
    }
    print_message("aerial perspective: %d hits, worst %.2f %% off surface x T + in-scattering\n", hits, 100 * aworst);
    assert_true(hits > 1000 && aworst < 0.005);
    scene_free(&s);
}

/* A GeoJSON line along the split meridian (WGS 84), 120 m wide, in green: every hit within 30 m of it is
 * green, none farther than 60 m + a drape texel is, and the line is there along the whole DEM. */
static void vectors_on_the_ground(void **st)
{
    (void)st;
    char file[256];
    snprintf(file, sizeof file, "%s/line.geojson", dir);
    FILE *f = fopen(file, "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {},"
               " \"geometry\": {\"type\": \"LineString\", \"coordinates\": [[%.9f, 46.8], [%.9f, 47.0]]}}]}\n",
            split_lon, split_lon);
    fclose(f);
    static float aov[W * H * AOV];
    scene s;
    char layer[400];
    snprintf(layer, sizeof layer, "\"%s/grey.tif\", \"vectors\": {\"file\": \"%s\", \"color\": [0, 1, 0], \"width\": 120}",
             dir, file);
    render_with(layer, aov, NULL, &s);
    scene_free(&s);
    OGRSpatialReferenceH u = srs_of(32633), g = srs_of(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(g, u);
    int near = 0, near_green = 0, far_green = 0;
    double worst = 0;
    for (int k = 0; k < W * H; k++) {
        const float *a = aov + (size_t)k * AOV;
        if (!isfinite(a[AOV_SLOT_DEPTH]))
            continue;
        double wx = a[AOV_SLOT_POSITION], wz = a[AOV_SLOT_POSITION + 2], z = 0;
        double n = GT[3] - (wz + DH * 100.0), e1 = split_lon, n1 = 46.8, e2 = split_lon, n2 = 47.0;
        OCTTransform(t, 1, &e1, &n1, &z);
        OCTTransform(t, 1, &e2, &n2, &z);
        double metres = fabs(wx + GT[0] + DW * 100.0 - (e1 + (e2 - e1) * (n - n1) / (n2 - n1)));
        const float *alb = a + AOV_SLOT_ALBEDO;
        bool green = alb[1] > 0.5f && alb[0] < 0.3f;
        if (metres < 30)
            near++, near_green += green;
        if (green)
            worst = fmax(worst, metres);
        far_green += green && metres > 60 + 60; /* half the width, and a drape texel (60 m: two across) */
    }
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(u);
    OSRDestroySpatialReference(g);
    print_message("vectors: %d of %d hits within 30 m of the line green, the farthest green hit %.1f m from it\n",
                  near_green, near, worst);
    assert_true(near >= 10 && near_green == near && far_green == 0);
}

/* Issue 58, item 8, then issue 52: a DEM too big for the driver was refused before it was read (llvmpipe holds
 * 1 GB in one texture: a 20000² DEM was refused after 88 s and 3.1 GB of reading); now one larger than the
 * terrain cache is streamed from disk instead (tests/geo/test_terrain_stream.c has its exactness), and
 * taken. A sparse tiled GeoTIFF of that size costs the test nothing to write. */
static void dem_too_big_is_streamed(void **st)
{
    (void)st;
    char file[256];
    snprintf(file, sizeof file, "%s/huge.tif", dir);
    const char *opts[] = {"TILED=YES", "SPARSE_OK=TRUE", "COMPRESS=DEFLATE", NULL};
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, 20000, 20000, 1, GDT_Float32, (char **)opts);
    assert_non_null(ds);
    GDALSetGeoTransform(ds, (double[6]){500000, 10, 0, 5200000, 0, -10});
    OGRSpatialReferenceH u = srs_of(32633);
    GDALSetSpatialRef(ds, u);
    OSRDestroySpatialReference(u);
    GDALClose(ds);
    char text[512];
    snprintf(text, sizeof text, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"terrain\": "
                                "{\"heightmap\": \"%s\", \"cache_mb\": 400}}", file);
    scene s;
    load_text(text, NULL, 0, &s);
    err_t e;
    double t0 = util_now();
    bool ok = render_set_scene(&s, NULL, &e);
    scene_free(&s);
    print_message("20000² DEM: %s in %.1f s\n", ok ? "streamed" : e.msg, util_now() - t0);
    assert_true(ok);
    assert_true(res_heightfield_streamed());
    render_release_scene();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(vectors_on_the_ground),
        cmocka_unit_test(dem_too_big_is_streamed),
        cmocka_unit_test(sky_matches_its_twin),
        cmocka_unit_test(halves_land_on_their_sides),
        cmocka_unit_test(opacity_zero_is_no_imagery),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
