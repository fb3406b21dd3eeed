/* vksky image I/O: the OpenEXR reader (OpenEXRCore C API). Errors follow io_error.h. */
#ifndef VKSKY_IO_EXR_READ_H
#define VKSKY_IO_EXR_READ_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Readers for tests/tools: read layer `layer_name` ("" = default R,G,B,A; a missing A reads as 1) from an EXR (any
   compression OpenEXRCore supports, HALF or FLOAT channels, scanline or tiled (level 0) parts, first part that has
   the layer) into a malloc'd float RGBA array (interleaved, row-major, top row of the data window first; free() it).
   Channels are matched by name. R, G and B must exist. */
int io_read_exr(const char *path, const char *layer_name, int *width, int *height, float **rgba, char *err,
                size_t err_size);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_EXR_READ_H */
