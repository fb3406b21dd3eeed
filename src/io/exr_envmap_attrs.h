/* vksky image I/O: the sky's header attributes (envmap, projection, the sun). Internal to src/io/; kept apart from
 * the writers so that other header attributes are added beside it, not inside it. */
#ifndef VKSKY_IO_EXR_ENVMAP_ATTRS_H
#define VKSKY_IO_EXR_ENVMAP_ATTRS_H
#include "io/exr_sky_attrs.h"
#include <openexr.h>

/* Adds the attributes `a` asks for to part `part` (before exr_write_header). */
exr_result_t io_exr_add_sky_attrs(exr_context_t ctxt, int part, const io_exr_sky_attrs *a);
#endif
