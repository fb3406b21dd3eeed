/* vksky image I/O: the OpenEXR writer (OpenEXRCore C API 3.1). See exr_write.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/exr_write.h"

#include "io/atomic_file.h"
#include "io/exr_common.h"
#include "io/half_float.h"
#include "io/io_error.h"

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#include <openexr.h>

int io_write_exr(const char *path, int width, int height, const io_exr_layer *layers, int layer_count, char *err,
                 size_t err_size)
{
    const char *p = io_safe_path(path);
    if (io_check_image_target(path, width, height, err, err_size) != 0) return -1;
    if (!layers || layer_count <= 0 || layer_count > 1000) {
        io_set_err(err, err_size, "cannot write '%s': invalid layer list (%d layers)", p, layer_count);
        return -1;
    }
    for (int i = 0; i < layer_count; ++i) {
        if (!layers[i].name || !layers[i].rgba_half) {
            io_set_err(err, err_size, "cannot write '%s': layer %d has no %s", p, i, layers[i].name ? "pixels" : "name");
            return -1;
        }
        if (strlen(layers[i].name) > IO_EXR_MAX_LAYER_NAME) {
            io_set_err(err, err_size, "cannot write '%s': layer %d name too long", p, i);
            return -1;
        }
        for (int j = 0; j < i; ++j) {
            if (strcmp(layers[i].name, layers[j].name) == 0) {
                io_set_err(err, err_size, "cannot write '%s': duplicate layer name '%s'", p, layers[i].name);
                return -1;
            }
        }
    }

    char tmp[PATH_MAX + 64];
    int fd = io_atomic_open(path, tmp, sizeof tmp, err, err_size);
    if (fd < 0) return -1;

    io_exr_out_stream stream = {fd, 0};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = io_exr_error_handler;
    init.user_data = &stream;
    init.write_fn = io_exr_fd_write;
    init.destroy_fn = io_exr_fd_destroy;

    exr_context_t ctxt = NULL;
    exr_result_t rc;
    const char *stage = "start";
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
    rc = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_ZIP);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    stage = "add channel";
    for (int l = 0; l < layer_count; ++l) {
        for (int c = 0; c < 4; ++c) {
            char name[IO_EXR_MAX_LAYER_NAME + 8];
            io_exr_channel_name(name, sizeof name, layers[l].name, c);
            rc = exr_add_channel(ctxt, part, name, EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
            if (rc != EXR_ERR_SUCCESS) goto fail;
        }
    }

    stage = "write header";
    rc = exr_write_header(ctxt);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    int32_t lines_per_chunk = 0;
    stage = "chunk layout";
    rc = exr_get_scanlines_per_chunk(ctxt, part, &lines_per_chunk);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    if (lines_per_chunk <= 0) {
        rc = EXR_ERR_INVALID_ATTR;
        goto fail;
    }

    for (int y = 0; y < height; y += lines_per_chunk) {
        exr_chunk_info_t cinfo;
        exr_encode_pipeline_t enc;
        memset(&cinfo, 0, sizeof cinfo);
        memset(&enc, 0, sizeof enc);
        stage = "chunk info";
        rc = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rc != EXR_ERR_SUCCESS) goto fail;
        stage = "encode init";
        rc = exr_encoding_initialize(ctxt, part, &cinfo, &enc);
        if (rc != EXR_ERR_SUCCESS) goto fail;

        /* The channel list is sorted by name in the file; map each back to (layer, component) by name. */
        for (int ch = 0; ch < enc.channel_count && rc == EXR_ERR_SUCCESS; ++ch) {
            exr_coding_channel_info_t *ci = &enc.channels[ch];
            int found = 0;
            for (int l = 0; l < layer_count && !found; ++l) {
                for (int c = 0; c < 4 && !found; ++c) {
                    char name[IO_EXR_MAX_LAYER_NAME + 8];
                    io_exr_channel_name(name, sizeof name, layers[l].name, c);
                    if (ci->channel_name && strcmp(ci->channel_name, name) == 0) {
                        size_t off = ((size_t)(cinfo.start_y) * (size_t)width) * 4u + (size_t)c;
                        ci->user_pixel_stride = 4 * (int32_t)sizeof(uint16_t);
                        ci->user_line_stride = width * 4 * (int32_t)sizeof(uint16_t);
                        ci->user_data_type = EXR_PIXEL_HALF;
                        ci->user_bytes_per_element = (int16_t)sizeof(uint16_t);
                        ci->encode_from_ptr = (const uint8_t *)(layers[l].rgba_half + off);
                        found = 1;
                    }
                }
            }
            if (!found) rc = EXR_ERR_INVALID_ARGUMENT;
        }
        stage = "encode";
        io_exr_compress_wrap wrap = {NULL};
        if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_choose_default_routines(ctxt, part, &enc);
        if (rc == EXR_ERR_SUCCESS && enc.compress_fn) {
            wrap.orig = enc.compress_fn;
            enc.encoding_user_data = &wrap;
            enc.compress_fn = io_exr_compress_no_expand;
        }
        if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_run(ctxt, part, &enc);
        exr_encoding_destroy(ctxt, &enc);
        if (rc != EXR_ERR_SUCCESS) goto fail;
    }

    stage = "finish";
    rc = exr_finish(&ctxt);
    ctxt = NULL;
    if (rc != EXR_ERR_SUCCESS || stream.err_no) goto fail;

    return io_atomic_commit(fd, tmp, path, err, err_size);

fail:
    if (ctxt) exr_finish(&ctxt);
    if (stream.err_no)
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(stream.err_no));
    else
        io_set_err(err, err_size, "cannot write '%s': OpenEXR %s failed: %s", p, stage, io_exr_msg(rc));
    io_atomic_abort(fd, tmp);
    return -1;
}
