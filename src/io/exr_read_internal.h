/* vksky image I/O: the EXR reader's internals, shared by its two source files and the fuzz harness (which reads
 * from memory, no file system in the loop). Internal to src/io/ and tests/.
 */
#ifndef VKSKY_IO_EXR_READ_INTERNAL_H
#define VKSKY_IO_EXR_READ_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include <openexr.h>

#include "io/exr_read.h"

/* Where the bytes come from: a file read with pread (fd >= 0), or a buffer in memory. `label` names it in
   messages (the path, or "<memory>"). */
typedef struct io_exr_src {
    const char *label;
    int fd;
    const uint8_t *data;
    uint64_t size;
} io_exr_src;

/* Largest decompressed chunk accepted: bounds what OpenEXRCore allocates per chunk for a hostile tile size. */
#define IO_EXR_READ_MAX_CHUNK_BYTES (512ull << 20)

/* Opens `path` as a source (0, or nonzero + err). io_exr_src_close closes a file source (memory: nothing). */
int io_exr_src_open_file(io_exr_src *src, const char *path, char *err, size_t err_size);
io_exr_src io_exr_src_memory(const void *data, size_t size);
void io_exr_src_close(io_exr_src *src);

/* Checks the magic number, then starts an OpenEXRCore read context over `src`, its messages captured. 0, or
   nonzero + one line in err ("LABEL: not an OpenEXR file ..."). */
int io_exr_src_start(const io_exr_src *src, exr_context_t *ctxt, char *err, size_t err_size);

/* The last message OpenEXRCore reported on this thread (its default text for rc when none). */
const char *io_exr_read_msg(exr_result_t rc);

/* Data window size of `part`, validated against the limits in exr_read.h. 0, or nonzero + err. */
int io_exr_part_size(exr_context_t ctxt, const io_exr_src *src, int part, int *width, int *height, char *err,
                     size_t err_size);

/* "LABEL: " + printf text, one line, into err. */
void io_exr_read_err(char *err, size_t err_size, const io_exr_src *src, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* The public functions over any source. */
int io_exr_read_info_src(const io_exr_src *src, io_exr_info *info, char *err, size_t err_size);
/* io_exr_read_rows on a source (rows < 0: every row, as io_exr_read_channels_src). */
int io_exr_read_rows_src(const io_exr_src *src, const char *const *names, int count, int row0, int rows, float *out,
                         char *err, size_t err_size);
int io_exr_read_channels_src(const io_exr_src *src, const char *const *names, int count, float *out, char *err,
                             size_t err_size);

#endif /* VKSKY_IO_EXR_READ_INTERNAL_H */
