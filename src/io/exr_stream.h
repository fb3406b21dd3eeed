/* vksky image I/O: an EXR written a band of rows at a time (OpenEXRCore scanline chunks), so that an image of any
 * size passes through a bounded buffer. One part, channels R,G,B,A HALF, ZIP; atomic like io_write_exr (temp file,
 * renamed at the end; nothing left at `path` on failure). Errors follow io_error.h. */
#ifndef VKSKY_IO_EXR_STREAM_H
#define VKSKY_IO_EXR_STREAM_H
#include "io/exr_sky_attrs.h"
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Largest side a streamed image may have (a cube map of 16384-pixel faces is 98304 rows). */
#define IO_STREAM_MAX_DIM (1 << 17)

typedef struct io_exr_stream io_exr_stream;

/* Starts the file (header written); NULL + err on failure (nothing left behind). */
io_exr_stream *io_exr_stream_open(const char *path, int width, int height, const io_exr_sky_attrs *attrs, char *err,
                                  size_t err_size);
/* The next `rows` rows, top to bottom, interleaved RGBA half floats (row stride width * 4). 0, or -1 + err (the
   stream is then aborted: call nothing else on it). */
int io_exr_stream_rows(io_exr_stream *s, const uint16_t *rgba_half, int rows, char *err, size_t err_size);
/* Physical light (issue 32): a stream fed float rows (RGBA, row stride width * 4), stored as FLOAT channels when
   store_float (values beyond half's 65504: the sun's disc in cd/m2), else converted to HALF. Then only
   io_exr_stream_rows_f32 feeds it. */
io_exr_stream *io_exr_stream_open_f32(const char *path, int width, int height, const io_exr_sky_attrs *attrs,
                                      bool store_float, char *err, size_t err_size);
int io_exr_stream_rows_f32(io_exr_stream *s, const float *rgba, int rows, char *err, size_t err_size);
/* After the last row: finishes and renames into place. 0, or -1 + err. Frees the stream either way. */
int io_exr_stream_finish(io_exr_stream *s, char *err, size_t err_size);
/* Gives up (temp file removed, nothing at `path`); frees the stream. NULL is accepted. */
void io_exr_stream_abort(io_exr_stream *s);
#endif
