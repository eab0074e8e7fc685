/* cli_mesh — `fathom mesh`'s options (cli.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "data/mesh/mesh.h"
#include "data/mesh/mesh_io.h"

static const char USAGE_MESH[] =
    "       fathom mesh --output FILE.ply|.stl|.obj|.glb|.3mf|.stp [--scene S | --formula F | --dem F]\n"
    "                   [--resolution N] [--box X0,Y0,Z0,X1,Y1,Z1] [--triangles N] [--tolerance V]\n"
    "                   [--one-shell] [--print-size MM] [--base M] [--set K=V]...\n"
    "  mesh: the scene's surface as a closed, manifold mesh (docs/guide/meshes.md): dual contouring of\n"
    "  the scene's own distance field on the GPU, in sparse blocks (sharp edges kept), N cells along\n"
    "  the box's longest side [256]; a DEM scene as a printable solid (surface, walls, base; N vertices\n"
    "  along its longest side [2048]). --triangles: simplify toward N (meshoptimizer) within V voxels\n"
    "  [1]; --one-shell: the largest piece only; --print-size: the longest side in millimetres (STL and\n"
    "  3MF: +Z up); --base: a DEM solid's base, metres below its lowest point [a tenth of its relief].\n"
    "  Prints the grid, the topology check, the vertices' distance to the field, time and memory.\n";

const char *cli_mesh_usage(void)
{
    return USAGE_MESH;
}

static bool positive(const char *name, const char *val, double hi, double *out, err_t *err)
{
    double v = 0;
    if (!util_parse_decimal(val, &v) || !(v > 0) || !(v <= hi))
        return err_set(err, "bad %s '%s': expected a number above 0 and at most %g", name, val, hi);
    *out = v;
    return true;
}

static bool parse_box(const char *val, double box[6], err_t *err)
{
    int used = 0;
    if (sscanf(val, "%lf,%lf,%lf,%lf,%lf,%lf%n", &box[0], &box[1], &box[2], &box[3], &box[4], &box[5], &used) != 6 ||
        val[used])
        return err_set(err, "bad --box '%s': expected X0,Y0,Z0,X1,Y1,Z1 (two corners)", val);
    for (int k = 0; k < 3; k++)
        if (!isfinite(box[k]) || !isfinite(box[k + 3]) || !(box[k + 3] > box[k]) || fabs(box[k]) > 1e15 ||
            fabs(box[k + 3]) > 1e15)
            return err_set(err, "bad --box '%s': each of X1, Y1, Z1 must be above X0, Y0, Z0 (finite)", val);
    return true;
}

bool cli_mesh_option(const char *name, const char *val, cli_options *o, err_t *err, bool *handled)
{
    *handled = true;
    double v = 0;
    if (!strcmp(name, "--resolution")) {
        if (!positive(name, val, MESH_MAX_RES, &v, err) || v != floor(v) || v < 2)
            return err_set(err, "bad --resolution '%s': expected a whole number of cells from 2 to %d", val, MESH_MAX_RES);
        o->mesh_resolution = (int)v;
    } else if (!strcmp(name, "--box")) {
        o->has_box = true;
        return parse_box(val, o->box, err);
    } else if (!strcmp(name, "--triangles")) {
        if (!positive(name, val, 2e9, &v, err) || v != floor(v) || v < 4)
            return err_set(err, "bad --triangles '%s': expected a whole number from 4 (a tetrahedron) up", val);
        o->mesh_triangles = (long)v;
    } else if (!strcmp(name, "--tolerance")) {
        return positive(name, val, 1e6, &o->mesh_tolerance, err);
    } else if (!strcmp(name, "--print-size")) {
        return positive(name, val, 1e7, &o->print_mm, err);
    } else if (!strcmp(name, "--base")) {
        return positive(name, val, 1e7, &o->mesh_base, err);
    } else {
        *handled = false;
    }
    return true;
}

bool cli_mesh_check(const cli_options *o, err_t *err)
{
    bool mesh_options = o->mesh_resolution || o->has_box || o->mesh_triangles || o->mesh_tolerance > 0 || o->one_shell ||
                        o->print_mm > 0 || o->mesh_base > 0;
    if (!o->mesh)
        return !mesh_options ||
               err_set(err, "--resolution, --box, --triangles, --tolerance, --one-shell, --print-size and --base belong "
                            "to fathom mesh");
    if (!o->output)
        return err_set(err, "fathom mesh needs --output FILE.ply (or .stl, .obj, .glb, .3mf, .stp)");
    const char *exporter = NULL;
    if (!mesh_io_format(o->output, &exporter, err))
        return false;
    if (o->width || o->spp || o->aovs || o->path || o->tile_count || o->has_camera || o->has_look_at || o->has_fov ||
        o->has_frames || o->strip_rows || o->video)
        return err_set(err, "fathom mesh writes a mesh: --size, --spp, --aov, --path, --tile, --camera, --look-at, --fov, "
                            "--frames, --strip-rows and --video do not apply");
    if (o->mesh_tolerance > 0 && !o->mesh_triangles)
        return err_set(err, "--tolerance bounds a simplification: give --triangles N too");
    return true;
}
