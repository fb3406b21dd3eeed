/* Test helper (header-only): writes EXRs straight through OpenEXRCore's encoder, independent of vksky's writers,
 * with known pixel values: single or multi-part, scanline or tiled, HALF/FLOAT/UINT channels, any compression the
 * library encodes, offset data windows and M44f camera attributes. Used by test_exr_read.c and to make the fuzz
 * seed corpus (fuzz/make_corpus.c). */
#ifndef VKSKY_TESTS_EXR_CORE_WRITER_H
#define VKSKY_TESTS_EXR_CORE_WRITER_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

typedef struct tw_channel {
    const char *name;
    int type; /* EXR_PIXEL_UINT / HALF / FLOAT */
} tw_channel;

typedef struct tw_part {
    const char *name;                /* part name (multi-part files need one) */
    int tiled, tile_w, tile_h;
    int compression;                 /* exr_compression_t */
    int x0, y0, w, h;                /* data window */
    int nch;
    tw_channel ch[8];
    int smooth;                      /* 1: smooth values (for lossy codecs), 0: random bits */
    int sampling;                    /* x and y sampling of the last channel (0 or 1: none) */
    int has_w2c, has_w2n;
    float w2c[16], w2n[16];
} tw_part;

static inline uint32_t tw_hash(uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    uint32_t h = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u ^ (c + 0x165667B1u) * 0xC2B2AE3Du ^ d * 0x27D4EB2Fu;
    h ^= h >> 15, h *= 0x2C1B3C6Du, h ^= h >> 12, h *= 0x297A2D39u, h ^= h >> 15;
    return h;
}

/* The stored bits of channel c of part p at data-window pixel (x, y) (x, y from 0). */
static inline uint32_t tw_bits(int p, int c, int x, int y, int type, int smooth)
{
    uint32_t h = tw_hash((uint32_t)p, (uint32_t)c, (uint32_t)x, (uint32_t)y);
    if (smooth) { /* a gentle ramp in half/float: lossy codecs keep it close */
        float v = 0.25f + 0.5f * (float)(x + 2 * y + 7 * c) / 512.0f;
        if (type == EXR_PIXEL_UINT) return (uint32_t)(x + 3 * y + c);
        if (type == EXR_PIXEL_FLOAT) {
            uint32_t u;
            memcpy(&u, &v, 4);
            return u;
        }
        /* v in [0.25, 4): a normal half; truncate to 10 mantissa bits */
        int e;
        float m = frexpf(v, &e); /* v = m 2^e, m in [0.5, 1) */
        uint32_t mant = (uint32_t)((m * 2.0f - 1.0f) * 1024.0f);
        return (uint32_t)((e - 1 + 15) << 10) | mant;
    }
    if (type == EXR_PIXEL_HALF) {
        h &= 0xffffu;
        if (((h >> 10) & 0x1fu) == 0x1fu) h &= ~0x4000u; /* no inf/NaN */
        return h;
    }
    if (type == EXR_PIXEL_FLOAT && ((h >> 23) & 0xffu) == 0xffu) h &= ~0x40000000u;
    return h;
}

/* The value the reader must return for those bits (decoded here by the definition, not by any library). */
static inline float tw_expect(uint32_t bits, int type)
{
    if (type == EXR_PIXEL_UINT) return (float)bits;
    if (type == EXR_PIXEL_FLOAT) {
        float f;
        memcpy(&f, &bits, 4);
        return f;
    }
    int s = (bits >> 15) & 1, e = (bits >> 10) & 0x1f, m = bits & 0x3ff;
    double v = e ? ldexp(1.0 + m / 1024.0, e - 15) : ldexp(m / 1024.0, -14);
    return (float)(s ? -v : v);
}

static inline int tw_bpe(int type) { return type == EXR_PIXEL_HALF ? 2 : 4; }

static inline int tw_write(const char *path, const tw_part *parts, int nparts)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    exr_result_t rc = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    for (int p = 0; p < nparts && rc == EXR_ERR_SUCCESS; ++p) {
        const tw_part *P = &parts[p];
        int idx = 0;
        rc = exr_add_part(ctxt, P->name, P->tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &idx);
        exr_attr_box2i_t dw;
        dw.min.x = P->x0, dw.min.y = P->y0, dw.max.x = P->x0 + P->w - 1, dw.max.y = P->y0 + P->h - 1;
        exr_attr_v2f_t swc;
        swc.x = swc.y = 0.0f;
        if (!rc) rc = exr_initialize_required_attr(ctxt, idx, &dw, &dw, 1.0f, &swc, 1.0f, EXR_LINEORDER_INCREASING_Y,
                                                   (exr_compression_t)P->compression);
        if (!rc && P->tiled)
            rc = exr_set_tile_descriptor(ctxt, idx, (uint32_t)P->tile_w, (uint32_t)P->tile_h, EXR_TILE_ONE_LEVEL,
                                         EXR_TILE_ROUND_DOWN);
        for (int c = 0; c < P->nch && !rc; ++c)
        {
            int smp = c == P->nch - 1 && P->sampling > 1 ? P->sampling : 1;
            rc = exr_add_channel(ctxt, idx, P->ch[c].name, (exr_pixel_type_t)P->ch[c].type,
                                 EXR_PERCEPTUALLY_LOGARITHMIC, smp, smp);
        }
        if (!rc && P->has_w2c) {
            exr_attr_m44f_t m;
            memcpy(m.m, P->w2c, sizeof m.m);
            rc = exr_attr_set_m44f(ctxt, idx, "worldToCamera", &m);
        }
        if (!rc && P->has_w2n) {
            exr_attr_m44f_t m;
            memcpy(m.m, P->w2n, sizeof m.m);
            rc = exr_attr_set_m44f(ctxt, idx, "worldToNDC", &m);
        }
    }
    if (!rc) rc = exr_write_header(ctxt);
    for (int p = 0; p < nparts && rc == EXR_ERR_SUCCESS; ++p) {
        const tw_part *P = &parts[p];
        int32_t sy = 0;
        int sx = P->w;
        if (P->tiled) {
            sx = P->tile_w;
            sy = P->tile_h;
        } else {
            rc = exr_get_scanlines_per_chunk(ctxt, p, &sy);
        }
        int nx = (P->w + sx - 1) / sx, ny = sy > 0 ? (P->h + sy - 1) / sy : 0;
        for (int cy = 0; cy < ny && !rc; ++cy) {
            for (int cx = 0; cx < nx && !rc; ++cx) {
                exr_chunk_info_t ci;
                exr_encode_pipeline_t enc;
                memset(&ci, 0, sizeof ci);
                memset(&enc, 0, sizeof enc);
                rc = P->tiled ? exr_write_tile_chunk_info(ctxt, p, cx, cy, 0, 0, &ci)
                              : exr_write_scanline_chunk_info(ctxt, p, P->y0 + cy * sy, &ci);
                if (rc) break;
                rc = exr_encoding_initialize(ctxt, p, &ci, &enc);
                if (rc) break;
                int x0 = cx * sx, y0 = cy * sy;
                uint8_t *bufs[8] = {0};
                for (int c = 0; c < enc.channel_count && !rc; ++c) {
                    exr_coding_channel_info_t *e = &enc.channels[c];
                    int k = 0; /* the channel list is sorted: find ours by name */
                    while (k < P->nch && strcmp(P->ch[k].name, e->channel_name) != 0) ++k;
                    int bpe = tw_bpe(P->ch[k].type), cw = e->width, chh = e->height; /* subsampled: fewer */
                    bufs[c] = (uint8_t *)malloc((size_t)(cw ? cw : 1) * (size_t)(chh ? chh : 1) * (size_t)bpe);
                    if (!bufs[c]) {
                        rc = EXR_ERR_OUT_OF_MEMORY;
                        break;
                    }
                    for (int y = 0; y < chh; ++y) {
                        for (int x = 0; x < cw; ++x) {
                            uint32_t b = tw_bits(p, k, x0 + x, y0 + y, P->ch[k].type, P->smooth);
                            memcpy(bufs[c] + ((size_t)y * cw + x) * bpe, bpe == 2 ? (void *)&(uint16_t){(uint16_t)b}
                                                                                   : (void *)&b, (size_t)bpe);
                        }
                    }
                    e->encode_from_ptr = bufs[c];
                    e->user_pixel_stride = bpe;
                    e->user_line_stride = cw * bpe;
                    e->user_data_type = (exr_pixel_type_t)P->ch[k].type;
                    e->user_bytes_per_element = (int16_t)bpe;
                }
                if (!rc) rc = exr_encoding_choose_default_routines(ctxt, p, &enc);
                if (!rc) rc = exr_encoding_run(ctxt, p, &enc);
                exr_encoding_destroy(ctxt, &enc);
                for (int c = 0; c < 8; ++c) free(bufs[c]);
            }
        }
    }
    exr_result_t frc = exr_finish(&ctxt);
    if (rc) {
        fprintf(stderr, "tw_write %s: %s\n", path, exr_get_default_error_message(rc));
        remove(path);
        return -1;
    }
    return frc ? -1 : 0;
}

#endif /* VKSKY_TESTS_EXR_CORE_WRITER_H */
