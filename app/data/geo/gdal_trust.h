/* gdal_trust — one trust policy for every file GDAL and OGR open for fathom (a DEM, imagery, vectors, a
 * track), whatever the entry point. A stranger's file is data: it may make GDAL read only local regular
 * files in the folders of the files the user named (and GDAL's and PROJ's own data), never the network,
 * a device, a FIFO, /proc or standard input. Four locks, each enough alone for its class:
 *   - drivers: every driver outside an allow-list of local file formats is deregistered (WMS, WCS, WFS,
 *     HTTP, PostgreSQL, … cannot be reached, also from inside a VRT);
 *   - network: GDAL's network file systems (/vsicurl/, /vsis3/, …) and /vsistdin/ replaced by ones that
 *     refuse, GDAL's HTTP fetch answered with an error, PROJ's networking off;
 *   - files: GDAL's local file system wrapped so that a read outside the allowed folders, or of anything
 *     but a regular file, fails as a missing file would (a VRT naming /etc/passwd, /dev/stdin, a FIFO);
 *   - VRTs scanned as they are opened, at any depth: a raw band (VRTRawRasterBand: a file's bytes as
 *     pixels) or a MEM::: source (the process's memory as pixels) refuses the VRT.
 * C++ behind a C interface: the file system is a GDAL C++ class. */
#ifndef FATHOM_GDAL_TRUST_H
#define FATHOM_GDAL_TRUST_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Once, after GDALAllRegister. */
void gdal_trust_init(void);

/* A path the user named (a file, or NETCDF:"file":VARIABLE): true when it is a local regular file, and
 * then its folder is one GDAL may read from; else false with the reason in why (why_size bytes). */
bool gdal_trust_path(const char *path, char *why, size_t why_size);

/* The allow-list, NULL-terminated, for GDALOpenEx's allowed drivers. */
const char *const *gdal_trust_drivers(void);

#ifdef __cplusplus
}
#endif

#endif
