/* vksky image I/O: the multilayer EXR writer (OpenEXRCore C API 3.1). One part, HALF channels, ZIP, written to a
   temporary and renamed (atomic_file.h). See exr_layers.h. The encode loop here serves both writers: io_write_exr
   (RGBA half layers, exr_write.c) and io_write_exr_layers (RGB or RGBA float layers, converted a chunk at a time so
   a large image never needs a second full-size copy). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/exr_layers.h"

#include "io/atomic_file.h"
#include "io/encode_settings.h"
#include "io/exr_common.h"
#include "io/exr_parallel.h"
#include "io/half_float.h"
#include "io/io_error.h"

#include <errno.h>
#include <stdbool.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#include <openexr.h>

/* A chunk that compression does not make smaller is stored raw: io_exr_compress_no_expand (exr_common.c says
   why), applied to every chunk by io_exr_encode_chunks. */

/* Channel k (0..3 = R, G, B, A) of layer `l`: which layer and component an encoder channel name stands for. */
static int find_channel(const io_exr_write_layer *layers, int layer_count, const char *name, int *layer, int *comp)
{
    for (int l = 0; l < layer_count; ++l) {
        for (int c = 0; c < layers[l].channels; ++c) {
            char n[IO_EXR_MAX_LAYER_NAME + 8];
            io_exr_channel_name(n, sizeof n, layers[l].name, c);
            if (name && strcmp(name, n) == 0) {
                *layer = l;
                *comp = c;
                return 1;
            }
        }
    }
    return 0;
}

/* Points encoder channel `ci` at the rows of one chunk: straight into half data, or into `scratch` filled with the
   float data converted to half (round to nearest even, io_float_to_half). */
static void feed_channel(exr_coding_channel_info_t *ci, const io_exr_write_layer *L, int comp, int width, int y0,
                         int rows, uint16_t *scratch)
{
    size_t first = (size_t)y0 * (size_t)width * (size_t)L->channels + (size_t)comp;
    if (L->f32 && L->store_float) {
        ci->encode_from_ptr = (const uint8_t *)(L->f32 + first);
        ci->user_pixel_stride = L->channels * (int32_t)sizeof(float);
        ci->user_line_stride = width * L->channels * (int32_t)sizeof(float);
        ci->user_data_type = EXR_PIXEL_FLOAT;
        ci->user_bytes_per_element = (int16_t)sizeof(float);
        return;
    }
    if (L->half) {
        ci->encode_from_ptr = (const uint8_t *)(L->half + first);
        ci->user_pixel_stride = L->channels * (int32_t)sizeof(uint16_t);
        ci->user_line_stride = width * L->channels * (int32_t)sizeof(uint16_t);
    } else {
        size_t n = (size_t)rows * (size_t)width;
        io_floats_to_halves(scratch, L->f32 + first, n, (size_t)L->channels);
        ci->encode_from_ptr = (const uint8_t *)scratch;
        ci->user_pixel_stride = (int32_t)sizeof(uint16_t);
        ci->user_line_stride = width * (int32_t)sizeof(uint16_t);
    }
    ci->user_data_type = EXR_PIXEL_HALF;
    ci->user_bytes_per_element = (int16_t)sizeof(uint16_t);
}

typedef struct feed_state {
    const io_exr_write_layer *layers;
    int layer_count, width, lines_per_chunk;
    uint16_t *scratch;           /* float data converted to half: one part per chunk (scratch_per_chunk halfs) */
    size_t scratch_per_chunk;    /* 0: no layer needs converting (half, or float stored as float: read in place) */
} feed_state;

/* io_exr_feed_fn: the chunk's channels (sorted by name in the file) mapped back to (layer, component) by name. */
static exr_result_t feed_chunk(void *user, exr_encode_pipeline_t *enc, int y, int rows)
{
    const feed_state *fs = user;
    for (int ch = 0; ch < enc->channel_count; ++ch) {
        exr_coding_channel_info_t *ci = &enc->channels[ch];
        int l = 0, c = 0;
        if (!find_channel(fs->layers, fs->layer_count, ci->channel_name, &l, &c)) return EXR_ERR_INVALID_ARGUMENT;
        /* Each chunk converts into its own part of the scratch (when any is needed), so chunks can be fed while
         * others are still being compressed on the worker threads. */
        size_t chunk = fs->scratch_per_chunk ? (size_t)(y / fs->lines_per_chunk) : 0;
        uint16_t *part = fs->scratch ? fs->scratch + chunk * fs->scratch_per_chunk +
                                           (size_t)ch * (size_t)fs->lines_per_chunk * (size_t)fs->width
                                     : NULL;
        feed_channel(ci, &fs->layers[l], c, fs->width, y, rows, part);
    }
    return EXR_ERR_SUCCESS;
}

/* Everything a writer is given, checked before a file is opened. 0, or -1 + err. */
static int check_layers(const char *path, int width, int height, const io_exr_write_layer *layers, int layer_count,
                        char *err, size_t err_size)
{
    const char *p = io_safe_path(path);
    if (io_check_image_target(path, width, height, err, err_size) != 0) return -1;
    if (!layers || layer_count <= 0 || layer_count > 1000) {
        io_set_err(err, err_size, "cannot write '%s': invalid layer list (%d layers; 1 to 1000 accepted)", p,
                   layer_count);
        return -1;
    }
    for (int i = 0; i < layer_count; ++i) {
        const io_exr_write_layer *L = &layers[i];
        size_t len = L->name ? strlen(L->name) : 0;
        if (!L->name || (!L->half && !L->f32)) {
            io_set_err(err, err_size, "cannot write '%s': layer %d has no %s", p, i, L->name ? "pixels" : "name");
            return -1;
        }
        if (L->channels != 3 && L->channels != 4) {
            io_set_err(err, err_size, "cannot write '%s': layer '%s' has %d channels (3 or 4 accepted)", p, L->name,
                       L->channels);
            return -1;
        }
        if (len > IO_EXR_MAX_LAYER_NAME || (len && (L->name[0] == '.' || L->name[len - 1] == '.'))) {
            io_set_err(err, err_size, "cannot write '%s': layer %d name '%.40s' %s", p, i, L->name,
                       len > IO_EXR_MAX_LAYER_NAME ? "too long" : "starts or ends with '.'");
            return -1;
        }
        for (int j = 0; j < i; ++j) {
            if (strcmp(L->name, layers[j].name) == 0) {
                io_set_err(err, err_size, "cannot write '%s': duplicate layer name '%s'", p, L->name);
                return -1;
            }
        }
    }
    return 0;
}

int io_exr_write_layers_half(const char *path, int width, int height, const io_exr_write_layer *layers,
                             int layer_count, const struct io_exr_meta *meta, char *err, size_t err_size)
{
    const char *p = io_safe_path(path);
    if (check_layers(path, width, height, layers, layer_count, err, err_size) != 0) return -1;
    char tmp[PATH_MAX + 64];
    int fd = io_atomic_open(path, tmp, sizeof tmp, err, err_size);
    if (fd < 0) return -1;

    io_exr_out_stream stream = {fd, 0};   /* written through exr_common.c's callbacks, as the streams' */
    exr_context_initializer_t init = io_exr_fd_initializer(&stream);

    exr_context_t ctxt = NULL;
    exr_result_t rc;
    const char *stage = "start";
    uint16_t *scratch = NULL;
    io_exr_clear_msg();

    rc = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    /* Names longer than 31 bytes need the "long names" file flag (only set when needed: old readers reject it). */
    int long_names = 0;
    for (int l = 0; l < layer_count; ++l) long_names |= strlen(layers[l].name) + 2 > 31;
    if (long_names) {
        stage = "enable long names";
        rc = exr_set_longname_support(ctxt, 1);
        if (rc != EXR_ERR_SUCCESS) goto fail;
    }

    int part = 0;
    stage = "add part";
    rc = exr_add_part(ctxt, "", EXR_STORAGE_SCANLINE, &part);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    stage = "header";
    rc = exr_initialize_required_attr_simple(ctxt, part, width, height,
                                             (exr_compression_t)io_encode_settings_get().exr_compression);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    stage = "compression";
    rc = io_exr_apply_compression_level(ctxt, part);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    if (meta) {
        stage = "attributes";
        rc = io_exr_set_meta(ctxt, part, meta);
        if (rc != EXR_ERR_SUCCESS) goto fail;
    }

    stage = "add channel";
    for (int l = 0; l < layer_count; ++l) {
        for (int c = 0; c < layers[l].channels; ++c) {
            char name[IO_EXR_MAX_LAYER_NAME + 8];
            io_exr_channel_name(name, sizeof name, layers[l].name, c);
            rc = exr_add_channel(ctxt, part, name, layers[l].f32 && layers[l].store_float ? EXR_PIXEL_FLOAT
                                                                                          : EXR_PIXEL_HALF,
                                 EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
            if (rc != EXR_ERR_SUCCESS) goto fail;
        }
    }

    stage = "write header";
    rc = exr_write_header(ctxt);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    int32_t lines_per_chunk = 0;
    stage = "chunk layout";
    rc = exr_get_scanlines_per_chunk(ctxt, part, &lines_per_chunk);
    if (rc == EXR_ERR_SUCCESS && (lines_per_chunk <= 0 || lines_per_chunk > 256)) rc = EXR_ERR_INVALID_ATTR;
    if (rc != EXR_ERR_SUCCESS) goto fail;

    int channel_count = 0;
    bool converts = false;   /* a float layer stored as half: converted chunk by chunk into the scratch */
    for (int l = 0; l < layer_count; ++l) {
        channel_count += layers[l].channels;
        converts |= layers[l].f32 && !layers[l].store_float;
    }
    /* Half layers and float layers stored as float are read in place; converted ones get a scratch part per chunk
     * (a half copy of the image), so every chunk compresses on the worker threads (exr_parallel.h) whatever the
     * pixel type: the photometric default writes float, and one thread would make it the bottleneck. */
    int chunks = (height + lines_per_chunk - 1) / lines_per_chunk;
    size_t per_chunk = converts ? (size_t)channel_count * (size_t)lines_per_chunk * (size_t)width : 0;
    scratch = converts ? (uint16_t *)malloc(per_chunk * (size_t)chunks * sizeof(uint16_t)) : NULL;
    if (converts && !scratch) {
        rc = EXR_ERR_OUT_OF_MEMORY;
        goto fail;
    }
    feed_state fs = {layers, layer_count, width, lines_per_chunk, scratch, per_chunk};
    stage = "encode";
    rc = io_exr_encode_chunks(ctxt, part, 0, chunks, lines_per_chunk, feed_chunk, &fs, io_encode_threads());
    if (rc != EXR_ERR_SUCCESS) goto fail;

    free(scratch);
    scratch = NULL;
    stage = "finish";
    rc = exr_finish(&ctxt);
    ctxt = NULL;
    if (rc != EXR_ERR_SUCCESS || stream.err_no) goto fail;

    return io_atomic_commit(fd, tmp, path, err, err_size);

fail:
    free(scratch);
    if (ctxt) exr_finish(&ctxt);
    if (stream.err_no)
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(stream.err_no));
    else
        io_set_err(err, err_size, "cannot write '%s': OpenEXR %s failed: %s", p, stage, io_exr_msg(rc));
    io_atomic_abort(fd, tmp);
    return -1;
}

int io_write_exr_layers(const char *path, int width, int height, const io_exr_out_layer *layers, int layer_count,
                        char *err, size_t err_size)
{
    return io_write_exr_layers_meta(path, width, height, layers, layer_count, NULL, err, err_size);
}

int io_write_exr_layers_meta(const char *path, int width, int height, const io_exr_out_layer *layers,
                             int layer_count, const struct io_exr_meta *meta, char *err, size_t err_size)
{
    if (!layers || layer_count <= 0 || layer_count > 1000)
        return check_layers(path, width, height, NULL, layer_count, err, err_size);
    io_exr_write_layer *w = (io_exr_write_layer *)calloc((size_t)layer_count, sizeof *w);
    if (!w) {
        io_set_err(err, err_size, "cannot write '%s': out of memory", io_safe_path(path));
        return -1;
    }
    for (int i = 0; i < layer_count; ++i) w[i] = (io_exr_write_layer){layers[i].name, layers[i].channels, NULL, layers[i].pixels, 0};
    int r = io_exr_write_layers_half(path, width, height, w, layer_count, meta, err, err_size);
    free(w);
    return r;
}
