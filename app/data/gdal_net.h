/* gdal_net — GDAL's network file systems (/vsicurl/, /vsis3/, /vsigs/, /vsiaz/, …) replaced by ones
 * that refuse, and PROJ's networking off: a DEM, or a VRT or zip inside it, never makes fathom send a
 * request. Files on disk and /vsizip/, /vsigzip/, /vsimem/ stay. C++ behind a C interface only because
 * GDAL's C call replaces a handler without freeing it: the replaced ones are kept here, reachable. */
#ifndef FATHOM_GDAL_NET_H
#define FATHOM_GDAL_NET_H

#ifdef __cplusplus
extern "C" {
#endif

/* Once, after GDALAllRegister. */
void gdal_network_off(void);

#ifdef __cplusplus
}
#endif

#endif
