/* vksky image I/O: the streamed EXR writer (see exr_stream.h). Rows arrive in bands of any height; whole chunks
 * (ZIP: 16 rows) are handed to the stream's chunk pool as soon as they are complete (exr_parallel.h: workers that
 * live as long as the file, so one band's chunks start while the band before's last ones compress); the remainder
 * waits in a one-chunk buffer. The compression is the process's (encode_settings.h: ZIP unless --exr-compression). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/exr_stream.h"
#include "io/atomic_file.h"
#include "io/exr_common.h"
#include "io/encode_settings.h"
#include "io/exr_envmap_attrs.h"
#include "io/exr_parallel.h"
#include "io/half_float.h"
#include "io/io_error.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct io_exr_stream {
    char path[PATH_MAX], tmp[PATH_MAX + 64];
    int fd;
    io_exr_out_stream out;
    exr_context_t ctxt;
    int width, height;
    int lines_per_chunk;
    int next_row;              /* rows received so far */
    int pending;               /* rows waiting in `chunk` (fewer than one chunk) */
    unsigned char *chunk;      /* lines_per_chunk rows */
    bool store_float;          /* FLOAT channels fed float rows (else HALF fed half rows) */
    uint16_t *scratch;         /* float rows stored as HALF: one band converted (io_exr_stream_rows_f32) */
    size_t scratch_rows;
    io_exr_pool *pool;         /* the encode threads, from the header to the finish */
};

/* Bytes per channel value of the rows the stream is fed. */
static size_t value_size(const io_exr_stream *s) { return s->store_float ? sizeof(float) : sizeof(uint16_t); }

static int fail(io_exr_stream *s, const char *stage, exr_result_t rc, char *err, size_t err_size)
{
    if (s->out.err_no)
        io_set_err(err, err_size, "cannot write '%s': %s", s->path, strerror(s->out.err_no));
    else
        io_set_err(err, err_size, "cannot write '%s': OpenEXR %s failed: %s", s->path, stage, io_exr_msg(rc));
    io_exr_stream_abort(s);
    return -1;
}

static io_exr_stream *stream_open(const char *path, int width, int height, const io_exr_sky_attrs *attrs,
                                  bool store_float, char *err, size_t err_size)
{
    if (!path || !path[0] || width < 1 || height < 1 || width > IO_STREAM_MAX_DIM || height > IO_STREAM_MAX_DIM) {
        io_set_err(err, err_size, "cannot write '%s': invalid image size %dx%d (expected 1..%d on each side)",
                   io_safe_path(path), width, height, IO_STREAM_MAX_DIM);
        return NULL;
    }
    io_exr_stream *s = calloc(1, sizeof *s);
    if (!s) {
        io_set_err(err, err_size, "cannot write '%s': out of memory", path);
        return NULL;
    }
    snprintf(s->path, sizeof s->path, "%s", path);
    s->width = width, s->height = height, s->fd = -1, s->store_float = store_float;
    s->fd = io_atomic_open(path, s->tmp, sizeof s->tmp, err, err_size);
    if (s->fd < 0) {
        free(s);
        return NULL;
    }
    s->out = (io_exr_out_stream){s->fd, 0};
    exr_context_initializer_t init = io_exr_fd_initializer(&s->out);
    io_exr_clear_msg();
    int part = 0;
    exr_result_t rc = exr_start_write(&s->ctxt, s->tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc != EXR_ERR_SUCCESS) return fail(s, "start", rc, err, err_size), NULL;
    rc = exr_add_part(s->ctxt, "", EXR_STORAGE_SCANLINE, &part);
    if (rc == EXR_ERR_SUCCESS) rc = exr_initialize_required_attr_simple(s->ctxt, part, width, height,
                                                 (exr_compression_t)io_encode_settings_get().exr_compression);
    for (int c = 0; c < 4 && rc == EXR_ERR_SUCCESS; ++c) {
        char name[8];
        io_exr_channel_name(name, sizeof name, "", c);
        rc = exr_add_channel(s->ctxt, part, name, store_float ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    }
    if (rc == EXR_ERR_SUCCESS) rc = io_exr_apply_compression_level(s->ctxt, part);
    if (rc == EXR_ERR_SUCCESS) rc = io_exr_add_sky_attrs(s->ctxt, part, attrs);
    if (rc == EXR_ERR_SUCCESS) rc = exr_write_header(s->ctxt);
    if (rc == EXR_ERR_SUCCESS) rc = exr_get_scanlines_per_chunk(s->ctxt, part, &s->lines_per_chunk);
    if (rc != EXR_ERR_SUCCESS) return fail(s, "header", rc, err, err_size), NULL;
    int chunks = (height + s->lines_per_chunk - 1) / s->lines_per_chunk, threads = io_encode_threads();
    s->pool = io_exr_pool_create(s->ctxt, part, s->lines_per_chunk, threads < chunks ? threads : chunks);
    if (!s->pool) return fail(s, "encode threads", EXR_ERR_OUT_OF_MEMORY, err, err_size), NULL;
    s->chunk = malloc((size_t)s->lines_per_chunk * (size_t)width * 4 * value_size(s));
    if (!s->chunk) return fail(s, "buffer", EXR_ERR_OUT_OF_MEMORY, err, err_size), NULL;
    return s;
}

io_exr_stream *io_exr_stream_open(const char *path, int width, int height, const io_exr_sky_attrs *attrs, char *err,
                                  size_t err_size)
{
    return stream_open(path, width, height, attrs, false, err, err_size);
}

io_exr_stream *io_exr_stream_open_f32(const char *path, int width, int height, const io_exr_sky_attrs *attrs,
                                      bool store_float, char *err, size_t err_size)
{
    return stream_open(path, width, height, attrs, store_float, err, err_size);
}

typedef struct rows_src {
    int width, y;               /* the row `base` holds */
    const unsigned char *base;  /* interleaved RGBA rows (half or float values), stride width * 4 values */
    int32_t size;               /* bytes per value */
    bool is_float;
} rows_src;

/* io_exr_feed_fn: the channels are stored sorted by name (A, B, G, R): each matched by its name. */
static exr_result_t feed_rows(void *user, exr_encode_pipeline_t *enc, int y, int rows)
{
    const rows_src *src = user;
    (void)rows;
    const unsigned char *first = src->base + (size_t)(y - src->y) * (size_t)src->width * 4 * (size_t)src->size;
    for (int ch = 0; ch < enc->channel_count; ++ch) {
        exr_coding_channel_info_t *ci = &enc->channels[ch];
        int c = ci->channel_name[0] == 'R' ? 0 : ci->channel_name[0] == 'G' ? 1 : ci->channel_name[0] == 'B' ? 2 : 3;
        ci->user_pixel_stride = 4 * src->size;
        ci->user_line_stride = src->width * 4 * src->size;
        ci->user_data_type = src->is_float ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF;
        ci->user_bytes_per_element = (int16_t)src->size;
        ci->encode_from_ptr = first + (size_t)c * (size_t)src->size;
    }
    return EXR_ERR_SUCCESS;
}

/* Hands `count` chunks, the first at row y, from rows of `rgba` (values of value_size) starting at that row to the
 * encode threads (exr_parallel.h); returns once the rows are packed (they may change then), maybe before the chunks
 * are written (io_exr_stream_finish waits for them). */
static exr_result_t write_chunks(io_exr_stream *s, int y, int count, const unsigned char *rgba)
{
    rows_src src = {s->width, y, rgba, (int32_t)value_size(s), s->store_float};
    return io_exr_pool_chunks(s->pool, y, count, feed_rows, &src);
}

static int stream_rows(io_exr_stream *s, const unsigned char *rgba, int rows, char *err, size_t err_size)
{
    size_t row_bytes = (size_t)s->width * 4 * value_size(s);
    if (rows < 0 || rows > s->height - s->next_row) {
        io_set_err(err, err_size, "cannot write '%s': %d rows past the image's %d", s->path, rows, s->height);
        io_exr_stream_abort(s);
        return -1;
    }
    int lpc = s->lines_per_chunk;
    while (rows > 0) {
        int chunk_y = s->next_row - s->pending;
        int chunk_rows = s->height - chunk_y < lpc ? s->height - chunk_y : lpc;
        exr_result_t rc = EXR_ERR_SUCCESS;
        if (s->pending == 0 && rows >= chunk_rows) {
            /* Whole chunks in the caller's band (the image's last, shorter chunk included): encoded in place. */
            int whole = 0, taken = 0;
            while (chunk_y + taken < s->height) {
                int n = s->height - (chunk_y + taken) < lpc ? s->height - (chunk_y + taken) : lpc;
                if (rows - taken < n) break;
                taken += n, ++whole;
            }
            rc = write_chunks(s, chunk_y, whole, rgba);
            rgba += (size_t)taken * row_bytes, rows -= taken, s->next_row += taken;
        } else {
            int take = chunk_rows - s->pending < rows ? chunk_rows - s->pending : rows;
            memcpy(s->chunk + (size_t)s->pending * row_bytes, rgba, (size_t)take * row_bytes);
            rgba += (size_t)take * row_bytes, rows -= take, s->pending += take, s->next_row += take;
            if (s->pending == chunk_rows) rc = write_chunks(s, chunk_y, 1, s->chunk), s->pending = 0;
        }
        if (rc != EXR_ERR_SUCCESS) return fail(s, "encode", rc, err, err_size);
    }
    return 0;
}

int io_exr_stream_rows(io_exr_stream *s, const uint16_t *rgba_half, int rows, char *err, size_t err_size)
{
    return stream_rows(s, (const unsigned char *)rgba_half, rows, err, err_size);
}

int io_exr_stream_rows_f32(io_exr_stream *s, const float *rgba, int rows, char *err, size_t err_size)
{
    if (s->store_float || rows <= 0) return stream_rows(s, (const unsigned char *)rgba, rows, err, err_size);
    size_t n = (size_t)rows * (size_t)s->width * 4;
    if ((size_t)rows > s->scratch_rows) {
        uint16_t *grown = realloc(s->scratch, n * sizeof(uint16_t));
        if (!grown) {
            io_set_err(err, err_size, "cannot write '%s': out of memory", s->path);
            io_exr_stream_abort(s);
            return -1;
        }
        s->scratch = grown, s->scratch_rows = (size_t)rows;
    }
    io_floats_to_halves(s->scratch, rgba, n, 1);
    return stream_rows(s, (const unsigned char *)s->scratch, rows, err, err_size);
}

int io_exr_stream_finish(io_exr_stream *s, char *err, size_t err_size)
{
    if (s->next_row != s->height || s->pending != 0) {
        io_set_err(err, err_size, "cannot write '%s': %d of %d rows given", s->path, s->next_row, s->height);
        io_exr_stream_abort(s);
        return -1;
    }
    exr_result_t rc = io_exr_pool_drain(s->pool);
    io_exr_pool_destroy(s->pool);
    s->pool = NULL;
    if (rc != EXR_ERR_SUCCESS) return fail(s, "encode", rc, err, err_size);
    rc = exr_finish(&s->ctxt);
    s->ctxt = NULL;
    if (rc != EXR_ERR_SUCCESS || s->out.err_no) return fail(s, "finish", rc, err, err_size);
    int result = io_atomic_commit(s->fd, s->tmp, s->path, err, err_size);
    free(s->chunk);
    free(s->scratch);
    free(s);
    return result;
}

void io_exr_stream_abort(io_exr_stream *s)
{
    if (!s) return;
    io_exr_pool_destroy(s->pool);   /* the workers stopped before the context goes */
    if (s->ctxt) exr_finish(&s->ctxt);
    if (s->fd >= 0) io_atomic_abort(s->fd, s->tmp);
    free(s->chunk);
    free(s->scratch);
    free(s);
}
