/* mesh_io — the binary's side of mesh files (data/mesh/mesh_io.h): formats, atomic writes, and the calls
 * into fathom_mesh.so (mesh_file.cpp). */
#include "data/mesh/mesh_io.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "data/lazy/lazy.h"

static const struct {
    const char *ext, *exporter;
} FORMATS[] = {{".ply", "plyb"}, {".stl", "stlb"}, {".obj", "objnomtl"}, {".glb", "glb2"}, {".3mf", "3mf"}, {".stp", "stp"}};

bool mesh_io_format(const char *path, const char **exporter, err_t *err)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    for (size_t i = 0; dot && (!slash || dot > slash) && i < sizeof FORMATS / sizeof FORMATS[0]; i++)
        if (!strcasecmp(dot, FORMATS[i].ext)) {
            *exporter = FORMATS[i].exporter;
            return true;
        }
    return err_set(err, "bad mesh file name '%s': it must end in .ply, .stl, .obj, .glb, .3mf or .stp", path);
}

static mesh_io_view view_of(const mesh *m)
{
    return (mesh_io_view){.pos = m->pos, .nrm = m->nrm, .col = m->col, .tri = m->tri, .nv = m->nv, .nt = m->nt};
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static unsigned le16(const unsigned char *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }

enum { ZIP_EOCD = 22, ZIP_CENTRAL = 46, ZIP_LOCAL = 30 }; /* record sizes (PKWARE's APPNOTE 4.3) */

/* The zip assimp wrote is whole: its end record last in the file, the central directory just before it,
 * every entry's local header where the directory says, its data before the directory. assimp's zip
 * writer does not check its writes (a full disk gave a success and a cut file). */
static bool zip_whole(const char *path)
{
    FILE *f = fopen(path, "rb");
    unsigned char e[ZIP_EOCD], h[ZIP_CENTRAL];
    long size = f && fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    bool ok = size >= ZIP_EOCD && fseek(f, size - ZIP_EOCD, SEEK_SET) == 0 && fread(e, 1, ZIP_EOCD, f) == ZIP_EOCD &&
              le32(e) == 0x06054b50 && le16(e + 20) == 0; /* no comment: the record is the last 22 bytes */
    long cd = ok ? (long)le32(e + 16) : 0, cd_size = ok ? (long)le32(e + 12) : 0;
    ok = ok && cd + cd_size == size - ZIP_EOCD;
    for (unsigned i = 0, n = ok ? le16(e + 10) : 0; ok && i < n; i++) {
        ok = fseek(f, cd, SEEK_SET) == 0 && fread(h, 1, ZIP_CENTRAL, f) == ZIP_CENTRAL && le32(h) == 0x02014b50;
        long local = ok ? (long)le32(h + 42) : 0, data = ok ? (long)le32(h + 20) : 0;
        cd += ZIP_CENTRAL + (ok ? (long)(le16(h + 28) + le16(h + 30) + le16(h + 32)) : 0);
        unsigned char l[ZIP_LOCAL];
        ok = ok && fseek(f, local, SEEK_SET) == 0 && fread(l, 1, ZIP_LOCAL, f) == ZIP_LOCAL && le32(l) == 0x04034b50 &&
             local + ZIP_LOCAL + le16(l + 26) + le16(l + 28) + data <= (long)le32(e + 16);
    }
    if (f)
        fclose(f);
    return ok;
}

/* 3MF is a zip archive assimp writes to a file only: into the temporary file, checked, then renamed. */
static bool write_by_file(const mesh_io_view *v, const char *exporter, const char *path, err_t *err)
{
    LAZY_FN(mesh_io_export_fn f, lazy_symbol(LAZY_MESH, "mesh_file_export", err));
    util_atomic a;
    if (!f || !util_atomic_open(&a, path, err))
        return false;
    char why[512] = "";
    if (!f(v, exporter, a.tmp, why, sizeof why) || !zip_whole(a.tmp)) {
        util_atomic_abort(&a);
        return err_set(err, "cannot write '%s': %s", path, why[0] ? why : "the archive does not read back whole (is "
                                                                         "the disk full?)");
    }
    return util_atomic_commit(&a, err);
}

bool mesh_io_write(const mesh *m, const char *path, err_t *err)
{
    const char *exporter = NULL;
    if (!mesh_io_format(path, &exporter, err))
        return false;
    if (m->nt == 0)
        return err_set(err, "no surface to write to '%s': the mesh is empty (is the object inside the box, and thicker "
                            "than a voxel? --box, --resolution)", path);
    if (m->nv > UINT32_MAX / 2)
        return err_set(err, "the mesh has %zu vertices, more than a mesh file holds: lower --resolution", m->nv);
    mesh_io_view v = view_of(m);
    if (!strcmp(exporter, "plyb")) /* assimp 5.2's binary PLY exporter declares uchar colours and writes floats:
                                      a file no reader (assimp's own included) reads right; PLY goes without */
        v.col = NULL;
    if (!strcmp(exporter, "3mf"))
        return write_by_file(&v, exporter, path, err);
    LAZY_FN(mesh_io_encode_fn f, lazy_symbol(LAZY_MESH, "mesh_file_encode", err));
    if (!f)
        return false;
    void *data;
    size_t size;
    char why[512];
    if (!f(&v, exporter, &data, &size, why, sizeof why))
        return err_set(err, "cannot write '%s': %s", path, why);
    util_atomic a;
    bool ok = util_atomic_open(&a, path, err);
    if (ok && fwrite(data, 1, size, a.f) != size) {
        util_atomic_abort(&a);
        ok = err_set(err, "cannot write '%s' (is the disk full?)", path);
    } else if (ok) {
        ok = util_atomic_commit(&a, err);
    }
    free(data);
    return ok;
}

bool mesh_io_read(const char *path, mesh *m, err_t *err)
{
    mesh_free(m);
    LAZY_FN(mesh_io_decode_fn f, lazy_symbol(LAZY_MESH, "mesh_file_decode", err));
    if (!f)
        return false;
    char why[512];
    float *pos = NULL;
    uint32_t *tri = NULL;
    size_t nv = 0, nt = 0;
    if (!f(path, &pos, &nv, &tri, &nt, why, sizeof why)) {
        free(pos);
        free(tri);
        return err_set(err, "%s", why);
    }
    m->pos = pos;
    m->tri = tri;
    m->nv = m->cap_v = nv;
    m->nt = m->cap_t = nt;
    const char *dot = strrchr(path, '.');
    if (dot && !strcasecmp(dot, ".stl")) /* its triangles each have their own corners: joined, as a slicer does */
        mesh_weld(m);
    m->nrm = util_calloc(m->nv ? 3 * m->nv : 1, sizeof(float), "mesh normals");
    return true;
}


bool mesh_io_simplify(mesh *m, size_t target, double tolerance, double *error, err_t *err)
{
    LAZY_FN(mesh_io_simplify_fn f, lazy_symbol(LAZY_MESH, "mesh_file_simplify", err));
    if (!f)
        return false;
    uint32_t *out = util_alloc((m->nt ? m->nt : 1) * 3 * sizeof(uint32_t), "mesh triangles");
    mesh_io_view v = view_of(m);
    float e = 0;
    size_t nt = f(&v, out, target, (float)tolerance, &e);
    free(m->tri);
    m->tri = out;
    m->nt = m->cap_t = nt;
    *error = e;
    mesh_compact(m);
    return true;
}
