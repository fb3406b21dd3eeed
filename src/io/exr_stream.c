/* vksky image I/O: the streamed EXR writer (see exr_stream.h). Rows arrive in bands of any height; whole chunks
 * (ZIP: 16 rows) are encoded as soon as they are complete, the remainder waits in a one-chunk buffer. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/exr_stream.h"
#include "io/atomic_file.h"
#include "io/exr_common.h"
#include "io/exr_envmap_attrs.h"
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
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = io_exr_error_handler;
    init.user_data = &s->out;
    init.write_fn = io_exr_fd_write;
    init.destroy_fn = io_exr_fd_destroy;
    io_exr_clear_msg();
    int part = 0;
    exr_result_t rc = exr_start_write(&s->ctxt, s->tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc != EXR_ERR_SUCCESS) return fail(s, "start", rc, err, err_size), NULL;
    rc = exr_add_part(s->ctxt, "", EXR_STORAGE_SCANLINE, &part);
    if (rc == EXR_ERR_SUCCESS) rc = exr_initialize_required_attr_simple(s->ctxt, part, width, height, EXR_COMPRESSION_ZIP);
    for (int c = 0; c < 4 && rc == EXR_ERR_SUCCESS; ++c) {
        char name[8];
        io_exr_channel_name(name, sizeof name, "", c);
        rc = exr_add_channel(s->ctxt, part, name, store_float ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    }
    if (rc == EXR_ERR_SUCCESS) rc = io_exr_add_sky_attrs(s->ctxt, part, attrs);
    if (rc == EXR_ERR_SUCCESS) rc = exr_write_header(s->ctxt);
    if (rc == EXR_ERR_SUCCESS) rc = exr_get_scanlines_per_chunk(s->ctxt, part, &s->lines_per_chunk);
    if (rc != EXR_ERR_SUCCESS) return fail(s, "header", rc, err, err_size), NULL;
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

/* Encodes the chunk starting at row y from rows of `rgba` (stride width * 4 values of value_size). */
static exr_result_t write_chunk(io_exr_stream *s, int y, const unsigned char *rgba)
{
    int32_t size = (int32_t)value_size(s);
    exr_chunk_info_t cinfo;
    exr_encode_pipeline_t enc;
    memset(&cinfo, 0, sizeof cinfo);
    memset(&enc, 0, sizeof enc);
    exr_result_t rc = exr_write_scanline_chunk_info(s->ctxt, 0, y, &cinfo);
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_initialize(s->ctxt, 0, &cinfo, &enc);
    if (rc != EXR_ERR_SUCCESS) return rc;
    /* The channels are stored sorted by name (A, B, G, R): match each by its name. */
    for (int ch = 0; ch < enc.channel_count; ++ch) {
        exr_coding_channel_info_t *ci = &enc.channels[ch];
        int c = ci->channel_name[0] == 'R' ? 0 : ci->channel_name[0] == 'G' ? 1 : ci->channel_name[0] == 'B' ? 2 : 3;
        ci->user_pixel_stride = 4 * size;
        ci->user_line_stride = s->width * 4 * size;
        ci->user_data_type = s->store_float ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF;
        ci->user_bytes_per_element = (int16_t)size;
        ci->encode_from_ptr = rgba + (size_t)c * (size_t)size;
    }
    io_exr_compress_wrap wrap = {NULL};
    rc = exr_encoding_choose_default_routines(s->ctxt, 0, &enc);
    if (rc == EXR_ERR_SUCCESS && enc.compress_fn) {
        wrap.orig = enc.compress_fn;
        enc.encoding_user_data = &wrap;
        enc.compress_fn = io_exr_compress_no_expand;
    }
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_run(s->ctxt, 0, &enc);
    exr_encoding_destroy(s->ctxt, &enc);
    return rc;
}

static int stream_rows(io_exr_stream *s, const unsigned char *rgba, int rows, char *err, size_t err_size)
{
    size_t row_values = (size_t)s->width * 4 * value_size(s);   /* bytes */
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
            /* A whole chunk in the caller's band: encode it in place. */
            rc = write_chunk(s, chunk_y, rgba);
            rgba += (size_t)chunk_rows * row_values, rows -= chunk_rows, s->next_row += chunk_rows;
        } else {
            int take = chunk_rows - s->pending < rows ? chunk_rows - s->pending : rows;
            memcpy(s->chunk + (size_t)s->pending * row_values, rgba, (size_t)take * row_values);
            rgba += (size_t)take * row_values, rows -= take, s->pending += take, s->next_row += take;
            if (s->pending == chunk_rows) rc = write_chunk(s, chunk_y, s->chunk), s->pending = 0;
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
    for (size_t i = 0; i < n; ++i) s->scratch[i] = io_float_to_half(rgba[i]);
    return stream_rows(s, (const unsigned char *)s->scratch, rows, err, err_size);
}

int io_exr_stream_finish(io_exr_stream *s, char *err, size_t err_size)
{
    if (s->next_row != s->height || s->pending != 0) {
        io_set_err(err, err_size, "cannot write '%s': %d of %d rows given", s->path, s->next_row, s->height);
        io_exr_stream_abort(s);
        return -1;
    }
    exr_result_t rc = exr_finish(&s->ctxt);
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
    if (s->ctxt) exr_finish(&s->ctxt);
    if (s->fd >= 0) io_atomic_abort(s->fd, s->tmp);
    free(s->chunk);
    free(s->scratch);
    free(s);
}
