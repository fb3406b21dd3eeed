/* vksky image I/O: the multilayer EXR writer in bands (exr_layers.h, io_exr_layers_stream_*): the header first, then
   the rows as they come, a chunk at a time, so that an image of any height passes through a band-sized buffer (the
   composite of an 8K plate, issue 28). One part, HALF channels, the compression of --exr-compression (encode_settings.h;
   ZIP by default); written to a temporary and renamed at the end (atomic_file.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/exr_layers.h"

#include "io/atomic_file.h"
#include "io/exr_common.h"
#include "io/exr_parallel.h"
#include "io/encode_settings.h"
#include "io/half_float.h"
#include "io/io_error.h"

#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

struct io_exr_layers_stream {
    char path[PATH_MAX], tmp[PATH_MAX + 64];
    int fd;
    io_exr_out_stream out;
    exr_context_t ctxt;
    int part, width, height, lines_per_chunk, next_row, layer_count, channel_count;
    char (*names)[IO_EXR_MAX_LAYER_NAME + 1];   /* layer names, copied */
    int *channels;                               /* per layer: 3 or 4 */
    uint16_t *scratch;                           /* scratch_chunks chunks of every channel, as half */
    int scratch_chunks;
    io_exr_pool *pool;                           /* the encode threads, from the header to the finish */
};

static void stream_fail(io_exr_layers_stream *s, const char *stage, exr_result_t rc, char *err, size_t err_size)
{
    const char *p = io_safe_path(s->path);
    if (s->out.err_no)
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(s->out.err_no));
    else
        io_set_err(err, err_size, "cannot write '%s': OpenEXR %s failed: %s", p, stage, io_exr_msg(rc));
    io_exr_layers_stream_abort(s);
}

io_exr_layers_stream *io_exr_layers_stream_open(const char *path, int width, int height,
                                                const io_exr_band_layer *layers, int layer_count,
                                                const struct io_exr_meta *meta, char *err, size_t err_size)
{
    const char *p = io_safe_path(path);
    if (io_check_image_target(path, width, height, err, err_size) != 0) return NULL;
    if (!layers || layer_count <= 0 || layer_count > 64 || strlen(path) >= PATH_MAX) {
        io_set_err(err, err_size, "cannot write '%s': invalid layer list (%d layers; 1 to 64 accepted)", p,
                   layer_count);
        return NULL;
    }
    for (int l = 0; l < layer_count; ++l) {
        size_t len = layers[l].name ? strlen(layers[l].name) : IO_EXR_MAX_LAYER_NAME + 1;
        if (len > IO_EXR_MAX_LAYER_NAME || (layers[l].channels != 3 && layers[l].channels != 4)) {
            io_set_err(err, err_size, "cannot write '%s': layer %d: a name of at most %d bytes and 3 or 4 channels "
                       "expected", p, l, IO_EXR_MAX_LAYER_NAME);
            return NULL;
        }
        for (int j = 0; j < l; ++j)
            if (!strcmp(layers[l].name, layers[j].name)) {
                io_set_err(err, err_size, "cannot write '%s': duplicate layer name '%s'", p, layers[l].name);
                return NULL;
            }
    }
    io_exr_layers_stream *s = calloc(1, sizeof *s);
    if (s) s->names = calloc((size_t)layer_count, sizeof *s->names), s->channels = calloc((size_t)layer_count, sizeof(int));
    if (!s || !s->names || !s->channels) {
        if (s) free(s->names), free(s->channels);
        free(s);
        io_set_err(err, err_size, "cannot write '%s': out of memory", p);
        return NULL;
    }
    snprintf(s->path, sizeof s->path, "%s", path);
    s->width = width, s->height = height, s->layer_count = layer_count;
    for (int l = 0; l < layer_count; ++l) {
        snprintf(s->names[l], sizeof s->names[l], "%s", layers[l].name);
        s->channels[l] = layers[l].channels;
        s->channel_count += layers[l].channels;
    }
    s->fd = io_atomic_open(path, s->tmp, sizeof s->tmp, err, err_size);
    if (s->fd < 0) {
        free(s->names), free(s->channels), free(s);
        return NULL;
    }
    s->out = (io_exr_out_stream){s->fd, 0};
    exr_context_initializer_t init = io_exr_fd_initializer(&s->out);
    io_exr_clear_msg();
    const char *stage = "start";
    exr_result_t rc = exr_start_write(&s->ctxt, s->tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    int long_names = 0;
    for (int l = 0; l < layer_count; ++l) long_names |= strlen(layers[l].name) + 2 > 31;
    if (rc == EXR_ERR_SUCCESS && long_names) stage = "enable long names", rc = exr_set_longname_support(s->ctxt, 1);
    if (rc == EXR_ERR_SUCCESS) stage = "add part", rc = exr_add_part(s->ctxt, "", EXR_STORAGE_SCANLINE, &s->part);
    if (rc == EXR_ERR_SUCCESS)
        stage = "header", rc = exr_initialize_required_attr_simple(s->ctxt, s->part, width, height,
                                                                   (exr_compression_t)io_encode_settings_get().exr_compression);
    /* --exr-compression zip:N's zlib level (encode_settings.h). */
    if (rc == EXR_ERR_SUCCESS) stage = "compression", rc = io_exr_apply_compression_level(s->ctxt, s->part);
    if (rc == EXR_ERR_SUCCESS && meta) stage = "attributes", rc = io_exr_set_meta(s->ctxt, s->part, meta);
    for (int l = 0; l < layer_count && rc == EXR_ERR_SUCCESS; ++l)
        for (int c = 0; c < layers[l].channels && rc == EXR_ERR_SUCCESS; ++c) {
            char name[IO_EXR_MAX_LAYER_NAME + 8];
            io_exr_channel_name(name, sizeof name, layers[l].name, c);
            stage = "add channel";
            rc = exr_add_channel(s->ctxt, s->part, name, EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
        }
    if (rc == EXR_ERR_SUCCESS) stage = "write header", rc = exr_write_header(s->ctxt);
    if (rc == EXR_ERR_SUCCESS) stage = "chunk layout", rc = exr_get_scanlines_per_chunk(s->ctxt, s->part, &s->lines_per_chunk);
    if (rc == EXR_ERR_SUCCESS && (s->lines_per_chunk <= 0 || s->lines_per_chunk > 256)) rc = EXR_ERR_INVALID_ATTR;
    if (rc == EXR_ERR_SUCCESS) {
        s->scratch = malloc((size_t)s->channel_count * (size_t)s->lines_per_chunk * (size_t)width * sizeof(uint16_t));
        if (!s->scratch) rc = EXR_ERR_OUT_OF_MEMORY;
        s->scratch_chunks = 1;
    }
    if (rc == EXR_ERR_SUCCESS) {
        int chunks = (height + s->lines_per_chunk - 1) / s->lines_per_chunk, threads = io_encode_threads();
        s->pool = io_exr_pool_create(s->ctxt, s->part, s->lines_per_chunk, threads < chunks ? threads : chunks);
        if (!s->pool) stage = "encode threads", rc = EXR_ERR_OUT_OF_MEMORY;
    }
    if (rc != EXR_ERR_SUCCESS) {
        stream_fail(s, stage, rc, err, err_size);
        return NULL;
    }
    return s;
}

int io_exr_layers_stream_rows_per_chunk(const io_exr_layers_stream *s) { return s->lines_per_chunk; }

/* Layer and component of an encoder channel name. */
static bool find_channel(const io_exr_layers_stream *s, const char *name, int *layer, int *comp)
{
    for (int l = 0; l < s->layer_count; ++l)
        for (int c = 0; c < s->channels[l]; ++c) {
            char n[IO_EXR_MAX_LAYER_NAME + 8];
            io_exr_channel_name(n, sizeof n, s->names[l], c);
            if (name && !strcmp(name, n)) {
                *layer = l, *comp = c;
                return true;
            }
        }
    return false;
}

/* One band's chunks as io_exr_encode_chunks feeds them: chunk (y - first) / lines_per_chunk converts into its own
 * part of the stream's band scratch, so that chunks compress on the worker threads while later ones are fed. */
typedef struct band_feed {
    io_exr_layers_stream *s;
    const io_exr_band_layer *layers;
    int first;
} band_feed;

static exr_result_t feed_band_chunk(void *user, exr_encode_pipeline_t *enc, int y, int rows)
{
    const band_feed *f = user;
    io_exr_layers_stream *s = f->s;
    size_t per_chunk = (size_t)s->channel_count * (size_t)s->lines_per_chunk * (size_t)s->width;
    uint16_t *chunk = s->scratch + (size_t)((y - f->first) / s->lines_per_chunk) * per_chunk;
    for (int ch = 0; ch < enc->channel_count; ++ch) {
        exr_coding_channel_info_t *ci = &enc->channels[ch];
        int l = 0, c = 0;
        if (!find_channel(s, ci->channel_name, &l, &c)) return EXR_ERR_INVALID_ARGUMENT;
        /* This chunk's rows of the band, converted to half into this channel's part of the chunk's scratch. */
        const io_exr_band_layer *L = &f->layers[l];
        int stride = L->stride > L->channels ? L->stride : L->channels;
        size_t at = (size_t)(y - f->first) * (size_t)s->width * (size_t)stride + (size_t)c;
        size_t n = (size_t)rows * (size_t)s->width;
        uint16_t *dst = chunk + (size_t)ch * (size_t)s->lines_per_chunk * (size_t)s->width;
        io_floats_to_halves(dst, L->pixels + at, n, (size_t)stride);
        ci->encode_from_ptr = (const uint8_t *)dst;
        ci->user_pixel_stride = (int32_t)sizeof(uint16_t);
        ci->user_line_stride = s->width * (int32_t)sizeof(uint16_t);
        ci->user_data_type = EXR_PIXEL_HALF;
        ci->user_bytes_per_element = (int16_t)sizeof(uint16_t);
    }
    return EXR_ERR_SUCCESS;
}

int io_exr_layers_stream_rows(io_exr_layers_stream *s, const io_exr_band_layer *layers, int rows, char *err,
                              size_t err_size)
{
    if (rows <= 0 || rows > s->height - s->next_row ||
        (s->next_row + rows < s->height && rows % s->lines_per_chunk != 0)) {
        io_set_err(err, err_size, "cannot write '%s': %d rows at row %d (whole chunks of %d rows, within %d rows)",
                   io_safe_path(s->path), rows, s->next_row, s->lines_per_chunk, s->height);
        io_exr_layers_stream_abort(s);
        return -1;
    }
    /* The band's chunks compress on the worker threads (exr_parallel.h, --threads; the same bytes for any count):
     * a scratch part per chunk of the largest band so far. */
    int chunks = (rows + s->lines_per_chunk - 1) / s->lines_per_chunk;
    if (chunks > s->scratch_chunks) {
        size_t per_chunk = (size_t)s->channel_count * (size_t)s->lines_per_chunk * (size_t)s->width;
        uint16_t *grown = realloc(s->scratch, per_chunk * (size_t)chunks * sizeof(uint16_t));
        if (!grown) {
            stream_fail(s, "band scratch", EXR_ERR_OUT_OF_MEMORY, err, err_size);
            return -1;
        }
        s->scratch = grown, s->scratch_chunks = chunks;
    }
    band_feed f = {s, layers, s->next_row};
    /* Returns once the band is packed (the scratch is free again); its chunks may still compress while the next band
     * comes (the stream's pool, exr_parallel.h); the finish waits for them. */
    exr_result_t rc = io_exr_pool_chunks(s->pool, s->next_row, chunks, feed_band_chunk, &f);
    if (rc != EXR_ERR_SUCCESS || s->out.err_no) {
        stream_fail(s, "encode", rc, err, err_size);
        return -1;
    }
    s->next_row += rows;
    return 0;
}

int io_exr_layers_stream_finish(io_exr_layers_stream *s, char *err, size_t err_size)
{
    if (s->next_row != s->height) {
        io_set_err(err, err_size, "cannot write '%s': %d of %d rows written", io_safe_path(s->path), s->next_row,
                   s->height);
        io_exr_layers_stream_abort(s);
        return -1;
    }
    exr_result_t rc = io_exr_pool_drain(s->pool);
    io_exr_pool_destroy(s->pool);
    s->pool = NULL;
    if (rc != EXR_ERR_SUCCESS) {
        stream_fail(s, "encode", rc, err, err_size);
        return -1;
    }
    rc = exr_finish(&s->ctxt);
    s->ctxt = NULL;
    if (rc != EXR_ERR_SUCCESS || s->out.err_no) {
        stream_fail(s, "finish", rc, err, err_size);
        return -1;
    }
    int r = io_atomic_commit(s->fd, s->tmp, s->path, err, err_size);
    free(s->scratch), free(s->names), free(s->channels), free(s);
    return r;
}

void io_exr_layers_stream_abort(io_exr_layers_stream *s)
{
    if (!s) return;
    io_exr_pool_destroy(s->pool);   /* the workers stopped before the context goes */
    if (s->ctxt) exr_finish(&s->ctxt);
    io_atomic_abort(s->fd, s->tmp);
    free(s->scratch), free(s->names), free(s->channels), free(s);
}
