/* vksky image I/O: the OpenEXR reader (OpenEXRCore C API 3.1). See exr_read.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/exr_read.h"

#include "io/exr_common.h"
#include "io/half_float.h"
#include "io/io_error.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

/* Our own unpack stage for the decode pipeline. OpenEXRCore 3.1.x picks specialised "interleaved" unpack
   routines by looking at the output pointers; for RGBA channels (stored sorted A,B,G,R) written into an RGBA
   buffer it picks a reversed-interleave path that returns the channels in the wrong order. The decompressed
   chunk layout is fixed by the file format (per scanline, per channel in file order, width little-endian
   values), so decode it directly. */
typedef struct exr_read_target {
    float *buf;      /* w*h RGBA floats */
    int w;           /* data window width */
    int x0, y0;      /* chunk origin relative to the data window */
    const int *comp; /* per pipeline channel: 0..3 = R,G,B,A slot, -1 = skip */
} exr_read_target;

static exr_result_t exr_unpack_rgba_float(exr_decode_pipeline_t *dec)
{
    const exr_read_target *t = (const exr_read_target *)dec->decoding_user_data;
    const uint8_t *src = (const uint8_t *)dec->unpacked_buffer;
    uint64_t avail = dec->chunk.unpacked_size, pos = 0;
    if (!t || !src) return EXR_ERR_CORRUPT_CHUNK;
    for (int ly = 0; ly < dec->chunk.height; ++ly) {
        int cury = dec->chunk.start_y + ly;
        for (int c = 0; c < dec->channel_count; ++c) {
            const exr_coding_channel_info_t *ci = &dec->channels[c];
            if (ci->height == 0 || ci->width <= 0) continue;
            if (ci->y_samples > 1 && (cury % ci->y_samples) != 0) continue;
            int bpe = ci->bytes_per_element;
            if (bpe != 2 && bpe != 4) return EXR_ERR_CORRUPT_CHUNK;
            uint64_t nbytes = (uint64_t)ci->width * (uint64_t)bpe;
            if (pos + nbytes > avail) return EXR_ERR_CORRUPT_CHUNK;
            int k = t->comp[c];
            if (k >= 0) {
                if (ci->width != dec->chunk.width || ci->height != dec->chunk.height) return EXR_ERR_CORRUPT_CHUNK;
                const uint8_t *s = src + pos;
                float *dst = t->buf + ((size_t)(t->y0 + ly) * (size_t)t->w + (size_t)t->x0) * 4u + (size_t)k;
                if (ci->data_type == EXR_PIXEL_HALF) {
                    for (int x = 0; x < ci->width; ++x, s += 2)
                        dst[4 * (size_t)x] = io_half_to_float((uint16_t)(s[0] | (s[1] << 8)));
                } else if (ci->data_type == EXR_PIXEL_FLOAT) {
                    for (int x = 0; x < ci->width; ++x, s += 4) {
                        uint32_t u = (uint32_t)s[0] | ((uint32_t)s[1] << 8) | ((uint32_t)s[2] << 16) |
                                     ((uint32_t)s[3] << 24);
                        float f;
                        memcpy(&f, &u, sizeof f);
                        dst[4 * (size_t)x] = f;
                    }
                } else {
                    return EXR_ERR_INVALID_ARGUMENT;
                }
            }
            pos += nbytes;
        }
    }
    return EXR_ERR_SUCCESS;
}

int io_read_exr(const char *path, const char *layer_name, int *width, int *height, float **rgba, char *err,
                size_t err_size)
{
    const char *p = io_safe_path(path);
    if (rgba) *rgba = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    if (!width || !height || !rgba) {
        io_set_err(err, err_size, "cannot read '%s': NULL output argument", p);
        return -1;
    }
    if (!layer_name) layer_name = "";
    if (strlen(layer_name) > IO_EXR_MAX_LAYER_NAME) {
        io_set_err(err, err_size, "cannot read '%s': layer name too long", p);
        return -1;
    }
    if (io_check_readable(path, err, err_size) != 0) return -1;

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = io_exr_error_handler;
    exr_context_t ctxt = NULL;
    float *buf = NULL;
    int *comp = NULL; /* channel index -> RGBA slot, grown per chunk */
    int comp_cap = 0;
    exr_result_t rc;
    const char *stage = "open";
    io_exr_clear_msg();

    rc = exr_start_read(&ctxt, path, &init);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    int nparts = 0;
    rc = exr_get_count(ctxt, &nparts);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    char names[4][IO_EXR_MAX_LAYER_NAME + 8];
    for (int c = 0; c < 4; ++c) io_exr_channel_name(names[c], sizeof names[c], layer_name, c);

    /* Find the first part holding the layer's R, G and B channels. */
    int part = -1;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    for (int pi = 0; pi < nparts && part < 0; ++pi) {
        const exr_attr_chlist_t *chl = NULL;
        if (exr_get_storage(ctxt, pi, &storage) != EXR_ERR_SUCCESS) continue;
        if (exr_get_channels(ctxt, pi, &chl) != EXR_ERR_SUCCESS || !chl) continue;
        int have = 0;
        for (int i = 0; i < chl->num_channels; ++i) {
            for (int c = 0; c < 3; ++c) {
                if (chl->entries[i].name.str && strcmp(chl->entries[i].name.str, names[c]) == 0) have |= 1 << c;
            }
        }
        if (have != 7) continue;
        if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
            exr_finish(&ctxt);
            io_set_err(err, err_size, "cannot read '%s': layer '%s' is in a deep part (not supported)", p, layer_name);
            return -1;
        }
        for (int i = 0; i < chl->num_channels; ++i) {
            const exr_attr_chlist_entry_t *e = &chl->entries[i];
            for (int c = 0; c < 4; ++c) {
                if (!e->name.str || strcmp(e->name.str, names[c]) != 0) continue;
                if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT) {
                    exr_finish(&ctxt);
                    io_set_err(err, err_size, "cannot read '%s': channel '%s' is not HALF or FLOAT", p, names[c]);
                    return -1;
                }
                if (e->x_sampling != 1 || e->y_sampling != 1) {
                    exr_finish(&ctxt);
                    io_set_err(err, err_size, "cannot read '%s': channel '%s' is subsampled", p, names[c]);
                    return -1;
                }
            }
        }
        part = pi;
    }
    if (part < 0) {
        exr_finish(&ctxt);
        io_set_err(err, err_size, "cannot read '%s': no layer '%s' (channels %s, %s, %s)", p, layer_name, names[0],
                names[1], names[2]);
        return -1;
    }

    exr_attr_box2i_t dw;
    stage = "data window";
    rc = exr_get_data_window(ctxt, part, &dw);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    int64_t w64 = (int64_t)dw.max.x - dw.min.x + 1, h64 = (int64_t)dw.max.y - dw.min.y + 1;
    if (w64 <= 0 || h64 <= 0 || w64 > IO_MAX_DIM || h64 > IO_MAX_DIM) {
        exr_finish(&ctxt);
        io_set_err(err, err_size, "cannot read '%s': unsupported data window %lldx%lld", p, (long long)w64,
                (long long)h64);
        return -1;
    }
    int w = (int)w64, h = (int)h64;
    size_t npix = (size_t)w * (size_t)h;
    if (npix > SIZE_MAX / (4u * sizeof(float))) {
        exr_finish(&ctxt);
        io_set_err(err, err_size, "cannot read '%s': image %dx%d too large", p, w, h);
        return -1;
    }
    buf = (float *)malloc(npix * 4u * sizeof(float));
    if (!buf) {
        exr_finish(&ctxt);
        io_set_err(err, err_size, "cannot read '%s': out of memory for %dx%d image", p, w, h);
        return -1;
    }
    for (size_t i = 0; i < npix; ++i) {
        buf[4 * i + 0] = buf[4 * i + 1] = buf[4 * i + 2] = 0.0f;
        buf[4 * i + 3] = 1.0f; /* missing A reads as 1 */
    }

    /* Chunk grid: scanline blocks, or the level-0 tiles of a tiled part. */
    int32_t step_x = w, step_y = 0;
    int64_t nx = 1, ny = 0;
    stage = "chunk layout";
    if (storage == EXR_STORAGE_SCANLINE) {
        rc = exr_get_scanlines_per_chunk(ctxt, part, &step_y);
    } else {
        uint32_t tx = 0, ty = 0;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        rc = exr_get_tile_descriptor(ctxt, part, &tx, &ty, &lm, &rm);
        if (rc == EXR_ERR_SUCCESS && (tx == 0 || ty == 0 || tx > (uint32_t)INT32_MAX || ty > (uint32_t)INT32_MAX))
            rc = EXR_ERR_INVALID_ATTR;
        step_x = (int32_t)tx;
        step_y = (int32_t)ty;
        nx = ((int64_t)w + step_x - 1) / step_x;
    }
    if (rc != EXR_ERR_SUCCESS) goto fail;
    if (step_y <= 0) {
        rc = EXR_ERR_INVALID_ATTR;
        goto fail;
    }
    ny = ((int64_t)h + step_y - 1) / step_y;

    for (int64_t cy = 0; cy < ny; ++cy) {
        for (int64_t cx = 0; cx < nx; ++cx) {
            exr_chunk_info_t cinfo;
            exr_decode_pipeline_t dec;
            memset(&cinfo, 0, sizeof cinfo);
            memset(&dec, 0, sizeof dec);
            int64_t x0, y0; /* chunk origin relative to the data window */
            stage = "chunk info";
            if (storage == EXR_STORAGE_SCANLINE) {
                rc = exr_read_scanline_chunk_info(ctxt, part, (int)(dw.min.y + cy * step_y), &cinfo);
                x0 = (int64_t)cinfo.start_x - dw.min.x;
                y0 = (int64_t)cinfo.start_y - dw.min.y;
            } else {
                rc = exr_read_tile_chunk_info(ctxt, part, (int)cx, (int)cy, 0, 0, &cinfo);
                x0 = cx * step_x; /* tile chunks report tile indices, not pixels */
                y0 = cy * step_y;
            }
            if (rc != EXR_ERR_SUCCESS) goto fail;
            if (x0 < 0 || y0 < 0 || cinfo.width <= 0 || cinfo.height <= 0 || x0 + cinfo.width > w ||
                y0 + cinfo.height > h) {
                rc = EXR_ERR_CORRUPT_CHUNK;
                goto fail;
            }
            stage = "decode init";
            rc = exr_decoding_initialize(ctxt, part, &cinfo, &dec);
            if (rc != EXR_ERR_SUCCESS) goto fail;
            if (dec.channel_count > comp_cap) {
                int *nc = (int *)realloc(comp, (size_t)dec.channel_count * sizeof(int));
                if (!nc) {
                    exr_decoding_destroy(ctxt, &dec);
                    rc = EXR_ERR_OUT_OF_MEMORY;
                    goto fail;
                }
                comp = nc;
                comp_cap = dec.channel_count;
            }
            /* Output pointers are set (the library needs them to choose its read/decompress stages) but the
               unpack stage is ours: see exr_unpack_rgba_float. */
            for (int ch = 0; ch < dec.channel_count; ++ch) {
                exr_coding_channel_info_t *ci = &dec.channels[ch];
                ci->decode_to_ptr = NULL;
                comp[ch] = -1;
                for (int c = 0; c < 4; ++c) {
                    if (ci->channel_name && strcmp(ci->channel_name, names[c]) == 0) {
                        size_t off = ((size_t)y0 * (size_t)w + (size_t)x0) * 4u + (size_t)c;
                        ci->user_pixel_stride = 4 * (int32_t)sizeof(float);
                        ci->user_line_stride = w * 4 * (int32_t)sizeof(float);
                        ci->user_data_type = EXR_PIXEL_FLOAT;
                        ci->user_bytes_per_element = (int16_t)sizeof(float);
                        ci->decode_to_ptr = (uint8_t *)(buf + off);
                        comp[ch] = c;
                    }
                }
            }
            exr_read_target target = {buf, w, (int)x0, (int)y0, comp};
            stage = "decode";
            rc = exr_decoding_choose_default_routines(ctxt, part, &dec);
            if (rc == EXR_ERR_SUCCESS) {
                dec.decoding_user_data = &target;
                dec.unpack_and_convert_fn = exr_unpack_rgba_float;
                rc = exr_decoding_run(ctxt, part, &dec);
            }
            exr_decoding_destroy(ctxt, &dec);
            if (rc != EXR_ERR_SUCCESS) goto fail;
        }
    }

    exr_finish(&ctxt);
    free(comp);
    *width = w;
    *height = h;
    *rgba = buf;
    return 0;

fail:
    if (ctxt) exr_finish(&ctxt);
    free(buf);
    free(comp);
    io_set_err(err, err_size, "cannot read '%s': OpenEXR %s failed: %s", p, stage, io_exr_msg(rc));
    return -1;
}
