/* vksky image I/O: the OpenEXR writer (OpenEXRCore C API). Atomic (atomic_file.h); errors follow io_error.h. */
#ifndef VKSKY_IO_EXR_WRITE_H
#define VKSKY_IO_EXR_WRITE_H

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

/* The same with header attributes (exr_meta.h; NULL: none). */
struct io_exr_meta;
int io_write_exr_meta(const char *path, int width, int height, const io_exr_layer *layers, int layer_count,
                      const struct io_exr_meta *meta, char *err, size_t err_size);

/* One RGBA layer of floats (physical light, issue 32): stored as FLOAT channels when store_float (values beyond
   half's 65504, such as the sun's disc in cd/m2), else converted to HALF. Otherwise as io_write_exr_meta. */
int io_write_exr_rgba_f32(const char *path, int width, int height, const float *rgba, int store_float,
                          const struct io_exr_meta *meta, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_EXR_WRITE_H */
