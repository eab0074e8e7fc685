/* lazy — the libraries that cost start-up time, loaded when a run first needs them.
 *
 * OpenImageIO pulls in some 260 shared libraries (ffmpeg, OpenCV, DCMTK, ...): mapping them took
 * 0.2-0.34 s of every start, `fathom --version` included. GDAL adds more. So OpenImageIO's side of
 * image_io (image_io.cpp: all but PNG writes and clean PNG and JPEG reads) and dem.c are built as
 * modules (fathom_image.so, fathom_dem.so, beside the binary or in <prefix>/lib/fathom), reached through
 * lazy_symbol by image_io.c and dem_lazy.c, which load the module on first call.
 *
 * A module is code fathom runs, so it is taken from those two places only, and only when it is a
 * regular file owned by root or the user, writable by no one else, and a whole ELF object (a cut one
 * would die of SIGBUS inside dlopen); anything else is refused in one line before dlopen.
 *
 * Loading one on a background thread while the GL starts was measured and dropped: dlopen holds the
 * dynamic loader's lock while it maps OpenImageIO's libraries, and the GL driver's own loading and
 * libepoxy's first dlsym of each GL function wait for it (a 64x36 shot took 0.60 s with it, 0.55 s
 * without, on 2 cores).
 */
#ifndef FATHOM_LAZY_H
#define FATHOM_LAZY_H

#include "util.h"

typedef enum lazy_module { LAZY_IMAGE, LAZY_DEM, LAZY_VIDEO, LAZY_MESH, LAZY_COUNT } lazy_module;

/* The address of `name` in module m, loading it on first use;
 * NULL with one line in err (may be NULL) when the module cannot be loaded or lacks the name. */
void *lazy_symbol(lazy_module m, const char *name, err_t *err);
/* Whether m is loaded (tests: a run that needs no images never loads OpenImageIO). */
bool lazy_loaded(lazy_module m);

/* Declares the function pointer `decl` (e.g. bool (*f)(const char *)), named f unless name says, and
 * sets it from `lookup`, a void * from lazy_symbol (dlsym's idiom: ISO C has no cast from an object
 * pointer to a function's). */
#define LAZY_FN(decl, lookup) LAZY_FN_NAMED(f, decl, lookup)
#define LAZY_FN_NAMED(name, decl, lookup) \
    decl;                                 \
    *(void **)&name = (lookup)

#endif
