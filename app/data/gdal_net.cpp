/* gdal_net — see gdal_net.h. */
#include "data/gdal_net.h"

#include <cpl_error.h>
#include <cpl_vsi.h>
#include <cpl_vsi_virtual.h>
#include <ogr_srs_api.h>

static const char *const NETWORK_PREFIXES[] = {
    "/vsicurl/", "/vsicurl_streaming/", "/vsis3/", "/vsis3_streaming/", "/vsigs/", "/vsigs_streaming/",
    "/vsiaz/", "/vsiaz_streaming/", "/vsiadls/", "/vsioss/", "/vsioss_streaming/", "/vsiswift/",
    "/vsiswift_streaming/", "/vsiwebhdfs/", "/vsihdfs/"};
enum { PREFIXES = sizeof NETWORK_PREFIXES / sizeof NETWORK_PREFIXES[0] };

/* GDAL's own handlers, replaced but not freed by InstallHandler: kept reachable for the process */
static VSIFilesystemHandler *replaced[PREFIXES];

static void *refuse_open(void *, const char *name, const char *)
{
    CPLError(CE_Failure, CPLE_OpenFailed, "'%s': fathom reads no DEM over the network; download it first", name);
    return nullptr;
}

static int refuse_stat(void *, const char *, VSIStatBufL *, int) { return -1; }

extern "C" void gdal_network_off(void)
{
    VSIFilesystemPluginCallbacksStruct *cb = VSIAllocFilesystemPluginCallbacksStruct();
    cb->open = refuse_open;
    cb->stat = refuse_stat;
    for (int i = 0; i < PREFIXES; i++) {
        replaced[i] = VSIFileManager::GetHandler(NETWORK_PREFIXES[i]);
        VSIInstallPluginHandler(NETWORK_PREFIXES[i], cb);
    }
    VSIFreeFilesystemPluginCallbacksStruct(cb);
    OSRSetPROJEnableNetwork(0); /* PROJ's grid downloads too */
}
