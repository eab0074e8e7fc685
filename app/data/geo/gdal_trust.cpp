/* gdal_trust — see gdal_trust.h. */
#include "data/geo/gdal_trust.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_http.h>
#include <cpl_minixml.h>
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

/* The one virtual file system a stranger's file may name: fathom's own memory files (GPX output). Every
 * other prefix GDAL registers (/vsicurl/ and /vsicurl?, /vsistdin?, /vsizip/, /vsigzip/, /vsisubfile/,
 * /vsisparse/, …) refuses: a network one connects, and an archive or a window on a file hides a VRT's
 * text from the scan below. */
static const char *const VSI_ALLOWED = "/vsimem/";

/* Folders GDAL reads its own tables from (CRS, datums): read, never a stranger's. */
static const char *const DATA_FOLDERS[] = {"/usr/share/gdal", "/usr/share/proj"};
/* Never read, whatever a file names: the kernel's and the devices' files look like files but are not. */
static const char *const NEVER[] = {"/proc/", "/sys/", "/dev/"};

static std::mutex roots_lock;
static std::vector<std::string> roots; /* real paths of folders GDAL may read from, without a trailing '/' */
static std::vector<std::string> files; /* real paths of files the user named (a link's target elsewhere) */

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
    for (const std::string &f : files)
        if (f == real)
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

/* Every name and value in a parsed XML tree (entities decoded, as the VRT driver reads them): none may
 * hold what no VRT may hold, and no value may be a whole dataset written inline ("<VRTDataset…"). */
static bool tree_harmless(const CPLXMLNode *n)
{
    for (; n; n = n->psNext) {
        const char *v = n->pszValue ? n->pszValue : "";
        for (const char *bad : VRT_REFUSED)
            if (contains_nocase(v, strlen(v), bad))
                return false;
        if (n->eType == CXT_Text && v[strspn(v, " \t\r\n")] == '<')
            return false;
        if (!tree_harmless(n->psChild))
            return false;
    }
    return true;
}

/* A regular file already allowed: false when it is a VRT holding what no VRT may hold, does not parse, or
 * is too big to scan. GDAL knows a VRT by its root element in the first bytes (no entity can spell an
 * element's name), so the first 64 KB decide whether the rest is read. */
static bool vrt_harmless(const char *name)
{
    FILE *f = fopen(name, "rb");
    if (!f)
        return false;
    std::vector<char> text(65536);
    size_t n = fread(text.data(), 1, text.size(), f);
    /* HDF5 (netCDF-4): its library reads external storage, links and virtual datasets by path, past this
     * jail; the signature sits at 0, 512, 1024, … (a user block before it) */
    for (size_t at = 0; at + 8 <= n; at = at ? 2 * at : 512)
        if (!memcmp(text.data() + at, "\x89HDF\r\n\x1a\n", 8)) {
            fclose(f);
            CPLError(CE_Failure, CPLE_NotSupported, "'%s' is HDF5 (netCDF-4), whose library reads other files by "
                                                    "itself: fathom does not open it; convert it (gdal_translate "
                                                    "to a GeoTIFF)", name);
            return false;
        }
    if (!contains_nocase(text.data(), n, "<VRTDataset") && !contains_nocase(text.data(), n, "<OGRVRTDataSource")) {
        fclose(f);
        return true;
    }
    text.resize(VRT_SCAN_MAX);
    n += fread(text.data() + n, 1, text.size() - n, f);
    fclose(f);
    if (n == text.size())
        return false; /* too big to scan */
    text.resize(n);
    for (const char *bad : VRT_REFUSED) /* the bytes as written, and below as GDAL decodes them */
        if (contains_nocase(text.data(), n, bad))
            return false;
    text.push_back('\0');
    CPLXMLNode *root = CPLParseXMLString(text.data());
    bool ok = root && tree_harmless(root);
    if (root)
        CPLDestroyXMLNode(root);
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

/* GDAL's own handlers, replaced but not freed by InstallHandler: kept reachable for the whole process, past the
 * static destructors (a static vector's storage is freed before LeakSanitizer looks, and its handlers then leak) */
static std::vector<VSIFilesystemHandler *> &replaced = *new std::vector<VSIFilesystemHandler *>;

static void *refuse_open(void *, const char *name, const char *)
{
    CPLError(CE_Failure, CPLE_OpenFailed, "'%s': fathom reads no file over the network, from standard input or "
                                          "through GDAL's virtual file systems; give the file itself", name);
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
    /* every registered prefix, and its "?" form (/vsicurl?url=…): GDAL 3.6 registers /vsicurl? apart and does
     * not list it among the prefixes */
    char **prefixes = VSIFileManager::GetPrefixes();
    for (int i = 0; prefixes && prefixes[i]; i++)
        for (int form = 0; form < 2 && strcmp(prefixes[i], VSI_ALLOWED) != 0; form++) {
            std::string p = prefixes[i];
            if (form == 1 && p.back() != '/')
                break;
            if (form == 1)
                p.back() = '?';
            replaced.push_back(VSIFileManager::GetHandler(p.c_str()));
            VSIInstallPluginHandler(p.c_str(), cb);
        }
    CSLDestroy(prefixes);
    VSIFreeFilesystemPluginCallbacksStruct(cb);
    replaced.push_back(VSIFileManager::GetHandler("/")); /* the default handler: local files */
    VSIFileManager::InstallHandler("", new jailed_files(replaced.back()));
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
    {
        std::lock_guard<std::mutex> hold(roots_lock);
        files.emplace_back(real);
    }
    /* the folder as named (a link named there does not open its target's folder); never the whole tree */
    char folder[PATH_MAX], real_folder[PATH_MAX];
    snprintf(folder, sizeof folder, "%s", file);
    char *slash = strrchr(folder, '/');
    if (slash)
        *slash = '\0';
    if (realpath(slash ? (*folder ? folder : "/") : ".", real_folder) && strcmp(real_folder, "/") != 0)
        allow_folder(real_folder);
    return true;
}
