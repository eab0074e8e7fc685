/* gdal_trust — see gdal_trust.h. */
#include "data/gdal_trust.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_http.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <cpl_vsi_virtual.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <mutex>
#include <string>
#include <vector>

/* Local file formats a DEM, imagery, vectors or a track come in, and the in-memory ones fathom itself
 * uses: nothing that speaks to a server or a database, whatever its name in a file. */
static const char *const DRIVERS[] = {
    /* rasters */
    "GTiff", "COG", "VRT", "MEM", "AAIGrid", "GSAG", "GSBG", "GS7BG", "SRTMHGT", "netCDF", "HFA", "EHdr",
    "ENVI", "USGSDEM", "XYZ", "PNG", "JPEG", "GIF", "BMP", "JP2OpenJPEG", "BT", "ERS", "DTED", "GPKG",
    /* vectors */
    "GPX", "KML", "LIBKML", "GeoJSON", "GeoJSONSeq", "ESRI Shapefile", "FlatGeobuf", "CSV", "GML", "OGR_VRT",
    "Memory", "MapInfo File", nullptr};

static const char *const NETWORK_PREFIXES[] = {
    "/vsicurl/", "/vsicurl_streaming/", "/vsis3/", "/vsis3_streaming/", "/vsigs/", "/vsigs_streaming/",
    "/vsiaz/", "/vsiaz_streaming/", "/vsiadls/", "/vsioss/", "/vsioss_streaming/", "/vsiswift/",
    "/vsiswift_streaming/", "/vsiwebhdfs/", "/vsihdfs/", "/vsistdin/"};
enum { PREFIXES = sizeof NETWORK_PREFIXES / sizeof NETWORK_PREFIXES[0] };

/* Folders GDAL reads its own tables from (CRS, datums): read, never a stranger's. */
static const char *const DATA_FOLDERS[] = {"/usr/share/gdal", "/usr/share/proj"};
/* Never read, whatever a file names: the kernel's and the devices' files look like files but are not. */
static const char *const NEVER[] = {"/proc/", "/sys/", "/dev/"};

static std::mutex roots_lock;
static std::vector<std::string> roots; /* real paths of folders GDAL may read from, without a trailing '/' */

static bool starts_with(const char *s, const char *prefix) { return strncmp(s, prefix, strlen(prefix)) == 0; }

/* A real path under a real folder: the folder itself, or below it ("/a/b" holds "/a/b/c", not "/a/bc"). */
static bool under(const char *real, const std::string &folder)
{
    size_t n = folder.size();
    return strncmp(real, folder.c_str(), n) == 0 && (real[n] == '/' || (n == 1 && folder[0] == '/'));
}

static void allow_folder(const char *real_folder)
{
    std::lock_guard<std::mutex> hold(roots_lock);
    for (const std::string &r : roots)
        if (r == real_folder)
            return;
    roots.emplace_back(real_folder);
}

/* May GDAL read this name? A regular file, resolved through every link, under an allowed folder. */
static bool may_read(const char *name)
{
    char real[PATH_MAX];
    struct stat st;
    if (!realpath(name, real) || stat(real, &st) != 0 || !S_ISREG(st.st_mode))
        return false;
    for (const char *never : NEVER)
        if (starts_with(real, never))
            return false;
    std::lock_guard<std::mutex> hold(roots_lock);
    for (const std::string &r : roots)
        if (under(real, r))
            return true;
    return false;
}

/* Opening an existing file ("r", "rb", "r+b"): jailed. Making a new one ("w", "a") is fathom's own output. */
static bool opens_existing(const char *access) { return access && access[0] == 'r'; }

/* What no VRT may hold, wherever it sits in a chain of VRTs: a raw band (a file's bytes as pixels: GDAL
 * 3.6 has no switch for it) and the MEM driver's open by pointer (the process's memory as pixels). */
static const char *const VRT_REFUSED[] = {"VRTRawRasterBand", "MEM:::"};
enum { VRT_SCAN_MAX = 64 << 20 }; /* bytes: a VRT mosaic of 100,000 tiles is ~30 MB */

static bool contains_nocase(const char *text, size_t n, const char *needle)
{
    size_t k = strlen(needle);
    for (size_t i = 0; i + k <= n; i++)
        if (!strncasecmp(text + i, needle, k))
            return true;
    return false;
}

/* A regular file already allowed: false when it is a VRT holding what no VRT may hold (or too big to scan). */
static bool vrt_harmless(const char *name)
{
    FILE *f = fopen(name, "rb");
    if (!f)
        return false;
    char head[1024];
    size_t n = fread(head, 1, sizeof head, f);
    bool vrt = contains_nocase(head, n, "<VRTDataset") || contains_nocase(head, n, "<OGRVRTDataSource");
    bool ok = true;
    if (vrt) {
        std::vector<char> all(VRT_SCAN_MAX);
        memcpy(all.data(), head, n);
        n += fread(all.data() + n, 1, all.size() - n, f);
        ok = n < all.size();
        for (const char *bad : VRT_REFUSED)
            ok = ok && !contains_nocase(all.data(), n, bad);
    }
    fclose(f);
    return ok;
}

/* GDAL's local file system, reads jailed; everything else as GDAL does it. */
class jailed_files final : public VSIFilesystemHandler
{
    VSIFilesystemHandler *inner;

  public:
    explicit jailed_files(VSIFilesystemHandler *h) : inner(h) {}
    VSIVirtualHandle *Open(const char *name, const char *access, bool set_error, CSLConstList options) override
    {
        if (opens_existing(access) && !may_read(name)) {
            errno = ENOENT;
            if (set_error)
                VSIError(VSIE_FileError, "'%s': fathom reads only regular files in the folders of the files you "
                                         "name", name);
            return nullptr;
        }
        if (opens_existing(access) && !vrt_harmless(name)) {
            errno = EACCES;
            CPLError(CE_Failure, CPLE_NotSupported, "'%s': a VRT with a raw band or a MEM::: source reads bytes "
                                                    "no one named; fathom refuses it", name);
            return nullptr;
        }
        return inner->Open(name, access, set_error, options);
    }
    int Stat(const char *name, VSIStatBufL *st, int flags) override { return inner->Stat(name, st, flags); }
    int Unlink(const char *name) override { return inner->Unlink(name); }
    int Rename(const char *from, const char *to) override { return inner->Rename(from, to); }
    int Mkdir(const char *name, long mode) override { return inner->Mkdir(name, mode); }
    int Rmdir(const char *name) override { return inner->Rmdir(name); }
    char **ReadDir(const char *name) override { return inner->ReadDir(name); }
    char **ReadDirEx(const char *name, int max) override { return inner->ReadDirEx(name, max); }
    char **SiblingFiles(const char *name) override { return inner->SiblingFiles(name); }
    int IsCaseSensitive(const char *name) override { return inner->IsCaseSensitive(name); }
    GIntBig GetDiskFreeSpace(const char *name) override { return inner->GetDiskFreeSpace(name); }
    int SupportsSparseFiles(const char *name) override { return inner->SupportsSparseFiles(name); }
    bool IsLocal(const char *name) override { return inner->IsLocal(name); }
    bool SupportsSequentialWrite(const char *name, bool tmp) override
    {
        return inner->SupportsSequentialWrite(name, tmp);
    }
    bool SupportsRandomWrite(const char *name, bool tmp) override { return inner->SupportsRandomWrite(name, tmp); }
};

/* GDAL's own handlers, replaced but not freed by InstallHandler: kept reachable for the process */
static VSIFilesystemHandler *replaced[PREFIXES + 1];

static void *refuse_open(void *, const char *name, const char *)
{
    CPLError(CE_Failure, CPLE_OpenFailed, "'%s': fathom reads no file over the network or from standard input; "
                                          "download it first", name);
    return nullptr;
}

static int refuse_stat(void *, const char *, VSIStatBufL *, int) { return -1; }

/* Every HTTP request a driver makes through GDAL (a GML schema, a WMS tile…) answered with an error. */
static CPLHTTPResult *refuse_fetch(const char *url, CSLConstList, GDALProgressFunc, void *, CPLHTTPFetchWriteFunc,
                                   void *, void *)
{
    CPLHTTPResult *r = static_cast<CPLHTTPResult *>(CPLCalloc(1, sizeof(CPLHTTPResult)));
    r->nStatus = 1;
    r->pszErrBuf = CPLStrdup(CPLSPrintf("'%s': fathom makes no network request", url));
    return r;
}

static void drivers_allowed_only(void)
{
    for (int i = GDALGetDriverCount() - 1; i >= 0; i--) {
        GDALDriverH d = GDALGetDriver(i);
        if (CSLFindString(const_cast<char **>(DRIVERS), GDALGetDriverShortName(d)) < 0) {
            GDALDeregisterDriver(d); /* as GDAL_SKIP does it: out of the manager, then freed */
            GDALDestroyDriver(d);
        }
    }
}

extern "C" void gdal_trust_init(void)
{
    drivers_allowed_only();
    VSIFilesystemPluginCallbacksStruct *cb = VSIAllocFilesystemPluginCallbacksStruct();
    cb->open = refuse_open;
    cb->stat = refuse_stat;
    for (int i = 0; i < PREFIXES; i++) {
        replaced[i] = VSIFileManager::GetHandler(NETWORK_PREFIXES[i]);
        VSIInstallPluginHandler(NETWORK_PREFIXES[i], cb);
    }
    VSIFreeFilesystemPluginCallbacksStruct(cb);
    replaced[PREFIXES] = VSIFileManager::GetHandler("/"); /* the default handler: local files */
    VSIFileManager::InstallHandler("", new jailed_files(replaced[PREFIXES]));
    CPLHTTPSetFetchCallback(refuse_fetch, nullptr);
    OSRSetPROJEnableNetwork(0); /* PROJ's grid downloads too */
    CPLSetConfigOption("GDAL_VRT_ENABLE_RAWRASTERBAND", "NO"); /* GDAL >= 3.7; vrt_harmless before that */
    CPLSetConfigOption("GDAL_VRT_ENABLE_PYTHON", "NO");
    for (const char *d : DATA_FOLDERS) {
        char real[PATH_MAX];
        if (realpath(d, real))
            allow_folder(real);
    }
}

const char *const *gdal_trust_drivers(void) { return DRIVERS; }

/* The file inside NETCDF:"file":VARIABLE or NETCDF:file:VARIABLE, into out. */
static bool netcdf_file(const char *path, char *out, size_t n)
{
    const char *f = path + strlen("NETCDF:");
    const char *end = *f == '"' ? strchr(f + 1, '"') : strrchr(f, ':');
    if (*f == '"')
        f++;
    if (!end || end <= f || (size_t)(end - f) >= n)
        return false;
    memcpy(out, f, (size_t)(end - f));
    out[end - f] = '\0';
    return true;
}

extern "C" bool gdal_trust_path(const char *path, char *why, size_t why_size)
{
    char file[PATH_MAX], real[PATH_MAX];
    size_t colon = strcspn(path, ":/");
    if (!strncasecmp(path, "NETCDF:", 7)) {
        if (!netcdf_file(path, file, sizeof file))
            return snprintf(why, why_size, "write a netCDF variable as NETCDF:\"FILE\":VARIABLE"), false;
    } else if (path[colon] == ':' || starts_with(path, "/vsi")) {
        return snprintf(why, why_size, "fathom opens local files only, not a server, a database or GDAL's "
                                       "virtual file systems; give the file itself"), false;
    } else {
        snprintf(file, sizeof file, "%s", path);
    }
    struct stat st;
    if (!realpath(file, real) || stat(real, &st) != 0)
        return snprintf(why, why_size, "%s", strerror(errno)), false;
    bool never = false;
    for (const char *n : NEVER)
        never = never || starts_with(real, n);
    if (!S_ISREG(st.st_mode) || never)
        return snprintf(why, why_size, "not a regular file (a device, FIFO or folder): give a file on disk"), false;
    *strrchr(real, '/') = '\0';
    allow_folder(*real ? real : "/");
    return true;
}
