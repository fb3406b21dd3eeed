/* vksky image I/O: OpenEXR (through the OpenEXRCore C API) and PNG (through libpng).
 *
 * This module knows nothing of Vulkan. All functions are safe to call with bad arguments: they never
 * crash, return -1 and write a one-line reason (no trailing newline) into err[err_size] (err may be NULL
 * or err_size 0, in which case the message is dropped). Writers are atomic: they write
 * "<dir>/.<basename>.tmp.<pid>" and rename() it over `path` only once everything succeeded; on failure the
 * temp file is removed and `path` is left untouched (no new file is created; an existing one is kept).
 */
#ifndef VKSKY_IO_IMAGE_IO_H
#define VKSKY_IO_IMAGE_IO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One named layer of an EXR: `name` "" means the default layer (channels R,G,B,A); otherwise channels are
   "<name>.R" etc. Pixels are interleaved RGBA half floats (uint16_t bits), row-major, top row first. */
typedef struct io_exr_layer {
    const char *name;
    const uint16_t *rgba_half;
} io_exr_layer;

/* Write a single-part scanline EXR, HALF channels, ZIP compression, all layers in one part. Atomic: writes
   "<dir>/.<basename>.tmp.<pid>" then rename()s; on any failure removes the temp file and leaves no file at `path`.
   Returns 0 on success; on failure returns -1 and writes a one-line reason (no trailing newline) into err[err_size],
   e.g. "cannot write 'dir/x.exr': No such file or directory". */
int io_write_exr(const char *path, int width, int height, const io_exr_layer *layers, int layer_count, char *err,
                 size_t err_size);

/* 8-bit RGBA PNG through libpng, same atomic temp+rename behaviour. `srgb` != 0 adds an sRGB chunk (perceptual
   intent, with the matching gAMA/cHRM fallback chunks the PNG spec recommends). */
int io_write_png(const char *path, int width, int height, const uint8_t *rgba8, int srgb, char *err, size_t err_size);

/* Readers for tests/tools: read layer `layer_name` ("" = default R,G,B,A; a missing A reads as 1) from an EXR (any
   compression OpenEXRCore supports, HALF or FLOAT channels, scanline or tiled (level 0) parts, first part that has
   the layer) into a malloc'd float RGBA array (interleaved, row-major, top row of the data window first; free() it).
   Channels are matched by name. R, G and B must exist. */
int io_read_exr(const char *path, const char *layer_name, int *width, int *height, float **rgba, char *err,
                size_t err_size);

/* Reads any PNG (gray/palette/16-bit/interlaced are converted) into a malloc'd RGBA8 array (free() it). */
int io_read_png(const char *path, int *width, int *height, uint8_t **rgba8, char *err, size_t err_size);

/* Checks that `path` can be created before expensive work: the directory exists and is writable (verified by
   creating and removing the writers' temp file, since access() always says yes to root). 0 ok, -1 + err. */
int io_check_writable(const char *path, char *err, size_t err_size);

/* float <-> half (round to nearest even, clamp finite values to +-65504, infinities stay infinite, NaN stays NaN). */
uint16_t io_float_to_half(float f);
float io_half_to_float(uint16_t h);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_IMAGE_IO_H */
