/* mesh_file — the module fathom_mesh.so (data/mesh/mesh_io.h): assimp's exporters and importer, and
 * meshoptimizer's simplifier, behind three extern "C" functions. */
#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <meshoptimizer.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>

extern "C" {
#include "data/mesh/mesh_io.h"
}

namespace {

/* One mesh, one material, one node under the root: what every exporter needs. The scene's destructor
 * frees all. */
aiScene *scene_of(const mesh_io_view *v)
{
    aiScene *s = new aiScene();
    s->mNumMaterials = 1;
    s->mMaterials = new aiMaterial *[1];
    s->mMaterials[0] = new aiMaterial();
    aiString name("fathom");
    s->mMaterials[0]->AddProperty(&name, AI_MATKEY_NAME);
    s->mNumMeshes = 1;
    s->mMeshes = new aiMesh *[1];
    aiMesh *m = s->mMeshes[0] = new aiMesh();
    m->mName = aiString("fathom");
    m->mMaterialIndex = 0;
    m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    m->mNumVertices = (unsigned)v->nv;
    m->mVertices = new aiVector3D[v->nv];
    m->mNormals = new aiVector3D[v->nv];
    if (v->col)
        m->mColors[0] = new aiColor4D[v->nv];
    for (size_t i = 0; i < v->nv; i++) {
        m->mVertices[i] = aiVector3D(v->pos[3 * i], v->pos[3 * i + 1], v->pos[3 * i + 2]);
        m->mNormals[i] = aiVector3D(v->nrm[3 * i], v->nrm[3 * i + 1], v->nrm[3 * i + 2]);
        if (v->col)
            m->mColors[0][i] = aiColor4D(v->col[3 * i], v->col[3 * i + 1], v->col[3 * i + 2], 1.0f);
    }
    m->mNumFaces = (unsigned)v->nt;
    m->mFaces = new aiFace[v->nt];
    for (size_t f = 0; f < v->nt; f++) {
        m->mFaces[f].mNumIndices = 3;
        m->mFaces[f].mIndices = new unsigned[3];
        for (int k = 0; k < 3; k++)
            m->mFaces[f].mIndices[k] = v->tri[3 * f + (size_t)k];
    }
    s->mRootNode = new aiNode(); /* the mesh in a child of the root: the 3MF exporter writes the root's children only */
    s->mRootNode->mName = aiString("root");
    aiNode *child = new aiNode();
    child->mName = aiString("fathom");
    child->mParent = s->mRootNode;
    child->mNumMeshes = 1;
    child->mMeshes = new unsigned[1];
    child->mMeshes[0] = 0;
    s->mRootNode->mNumChildren = 1;
    s->mRootNode->mChildren = new aiNode *[1];
    s->mRootNode->mChildren[0] = child;
    return s;
}

} // namespace

extern "C" bool mesh_file_encode(const mesh_io_view *v, const char *exporter,
                                                                          void **data, size_t *size, char *err, size_t n)
{
    *data = nullptr;
    try {
        aiScene *s = scene_of(v);
        const aiExportDataBlob *blob = aiExportSceneToBlob(s, exporter, 0);
        delete s;
        if (!blob) {
            snprintf(err, n, "assimp could not write the mesh as %s: %s", exporter, aiGetErrorString());
            return false;
        }
        if (blob->next) { /* a second file (a material, a buffer): not a format fathom offers */
            aiReleaseExportBlob(blob);
            snprintf(err, n, "assimp's %s exporter wrote more than one file", exporter);
            return false;
        }
        *size = blob->size;
        *data = malloc(blob->size ? blob->size : 1);
        if (*data)
            memcpy(*data, blob->data, blob->size);
        aiReleaseExportBlob(blob);
        if (!*data)
            snprintf(err, n, "out of memory for a %zu-byte mesh file", *size);
        return *data != nullptr;
    } catch (const std::bad_alloc &) {
        snprintf(err, n, "out of memory building the mesh for assimp (%zu triangles)", v->nt);
        return false;
    }
}

/* For an exporter that writes only to files (3MF: a zip archive), to path. */
extern "C" bool mesh_file_export(const mesh_io_view *v, const char *exporter, const char *path, char *err, size_t n)
{
    try {
        aiScene *s = scene_of(v);
        aiReturn r = aiExportScene(s, exporter, path, 0);
        delete s;
        if (r != aiReturn_SUCCESS)
            snprintf(err, n, "assimp could not write the mesh as %s: %s", exporter, aiGetErrorString());
        return r == aiReturn_SUCCESS;
    } catch (const std::bad_alloc &) {
        snprintf(err, n, "out of memory building the mesh for assimp (%zu triangles)", v->nt);
        return false;
    }
}

extern "C" bool mesh_file_decode(const char *path, float **pos, size_t *nv,
                                                                          uint32_t **tri, size_t *nt, char *err, size_t n)
{
    const aiScene *s = aiImportFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!s || !s->mNumMeshes) {
        snprintf(err, n, "assimp could not read '%s': %s", path, s ? "no mesh in it" : aiGetErrorString());
        if (s)
            aiReleaseImport(s);
        return false;
    }
    size_t vcount = 0, fcount = 0;
    for (unsigned k = 0; k < s->mNumMeshes; k++) {
        vcount += s->mMeshes[k]->mNumVertices;
        fcount += s->mMeshes[k]->mNumFaces;
    }
    *pos = (float *)malloc(vcount * 3 * sizeof(float) + 1);
    *tri = (uint32_t *)malloc(fcount * 3 * sizeof(uint32_t) + 1);
    *nv = *nt = 0;
    for (unsigned k = 0; *pos && *tri && k < s->mNumMeshes; k++) {
        const aiMesh *m = s->mMeshes[k];
        size_t base = *nv;
        for (unsigned i = 0; i < m->mNumVertices; i++, ++*nv)
            for (int c = 0; c < 3; c++)
                (*pos)[3 * *nv + (size_t)c] = m->mVertices[i][c];
        for (unsigned f = 0; f < m->mNumFaces; f++)
            if (m->mFaces[f].mNumIndices == 3) {
                for (int c = 0; c < 3; c++)
                    (*tri)[3 * *nt + (size_t)c] = (uint32_t)(base + m->mFaces[f].mIndices[c]);
                ++*nt;
            }
    }
    aiReleaseImport(s);
    if (!*pos || !*tri)
        snprintf(err, n, "out of memory reading '%s'", path);
    return *pos && *tri;
}

extern "C" size_t mesh_file_simplify(const mesh_io_view *v, uint32_t *out,
                                                                              size_t target_triangles, float tolerance,
                                                                              float *error)
{
    float scale = meshopt_simplifyScale(v->pos, v->nv, 3 * sizeof(float));
    float relative = scale > 0 ? tolerance / scale : 0;
    size_t n = meshopt_simplify(out, v->tri, 3 * v->nt, v->pos, v->nv, 3 * sizeof(float), 3 * target_triangles,
                                relative, 0, error);
    *error *= scale;
    return n / 3;
}
