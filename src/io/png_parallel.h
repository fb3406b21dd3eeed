/* vksky image I/O: a PNG's image data (IDAT) compressed on worker threads, the way pigz compresses (issue 27). Internal
 * to src/io/: png_io.c and png_stream.c call it after libpng has written the signature and the header chunks.
 *
 * Why by hand: libpng drives one zlib stream row by row, so its deflate runs on one core (13.7 frames/s at 720p on
 * the H100 host, 16 cores idle). A zlib stream can be cut into blocks of rows that are deflated independently and
 * concatenated: each block but the last ends on a byte boundary (Z_SYNC_FLUSH), each starts with the 32 KiB of
 * filtered data before it as a preset dictionary (so the ratio barely changes), and the stream's Adler-32 is
 * combined from the blocks' (adler32_combine). Only the IDAT assembly is ours; the header chunks stay libpng's. The
 * blocks are fixed by the image's width (BLOCK_BYTES of rows), never by the thread count or by how the caller hands
 * rows over, so every thread count above 1 writes the same bytes; --threads 1 keeps libpng's writer (today's
 * bytes). Filters: libpng's default choice per row (the smallest sum of absolute differences over the five). */
#ifndef VKSKY_IO_PNG_PARALLEL_H
#define VKSKY_IO_PNG_PARALLEL_H
#include <stdint.h>
#include <stdio.h>

typedef struct io_png_par io_png_par;

/* Whether an RGBA8 image of this size is written in parallel with `threads` threads: more than one thread and at
 * least two blocks of rows. */
int io_png_par_wanted(int width, int height, int threads);
/* A writer appending IDAT chunks and IEND to fp (positioned after the header chunks). NULL when out of memory. */
io_png_par *io_png_par_create(FILE *fp, int width, int height, int threads);
/* The next `rows` rows (RGBA8, stride width * 4), in any batch sizes. 0, or -1: *err_no holds an errno (a failed
 * write; EIO when unknown) or 0 with msg filled (zlib, memory). */
int io_png_par_rows(io_png_par *p, const uint8_t *rgba8, int rows);
/* After the last row: the last block, the stream's trailer and IEND. 0 or -1 as io_png_par_rows. */
int io_png_par_finish(io_png_par *p);
/* The error of the last failed call: errno (0 when it was not a system error) and a message. */
int io_png_par_errno(const io_png_par *p);
const char *io_png_par_message(const io_png_par *p);
void io_png_par_free(io_png_par *p);
#endif
