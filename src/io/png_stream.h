/* vksky image I/O: a PNG written a band of rows at a time (libpng rows), for images of any size in bounded memory.
 * 8-bit RGBA, sRGB chunk; atomic (temp file renamed at the end). Errors follow io_error.h. */
#ifndef VKSKY_IO_PNG_STREAM_H
#define VKSKY_IO_PNG_STREAM_H
#include <stddef.h>
#include <stdint.h>

typedef struct io_png_stream io_png_stream;

/* NULL + err on failure (nothing left behind). Sides up to IO_STREAM_MAX_DIM (io/exr_stream.h). */
io_png_stream *io_png_stream_open(const char *path, int width, int height, char *err, size_t err_size);
/* The next `rows` rows, RGBA8, row stride width * 4. 0, or -1 + err (the stream is then aborted). */
int io_png_stream_rows(io_png_stream *s, const uint8_t *rgba8, int rows, char *err, size_t err_size);
/* After the last row: 0, or -1 + err. Frees the stream either way. */
int io_png_stream_finish(io_png_stream *s, char *err, size_t err_size);
void io_png_stream_abort(io_png_stream *s);
#endif
