/* vksky image I/O: PNG writer and reader (libpng). The writer is atomic (atomic_file.h); errors follow io_error.h. */
#ifndef VKSKY_IO_PNG_IO_H
#define VKSKY_IO_PNG_IO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* 8-bit RGBA PNG through libpng, atomic (atomic_file.h). `srgb` != 0 adds an sRGB chunk (perceptual
   intent, with the matching gAMA/cHRM fallback chunks the PNG spec recommends). */
int io_write_png(const char *path, int width, int height, const uint8_t *rgba8, int srgb, char *err, size_t err_size);

/* Reads any PNG (gray/palette/16-bit/interlaced are converted) into a malloc'd RGBA8 array (free() it). */
int io_read_png(const char *path, int *width, int *height, uint8_t **rgba8, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_IO_PNG_IO_H */
