/* vksky image I/O: reading named channels of an untrusted EXR as float. See exr_read.h. Every size the file states
   is checked against the file's real size before the library allocates for it: the chunk table, each chunk's
   packed bytes, each chunk's unpacked bytes. */
#include "io/exr_read_internal.h"
#include "io/exr_deflate.h"

#include "io/encode_settings.h"

#include <libdeflate.h>
#include <pthread.h>
#include <stdatomic.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Our own unpack stage. OpenEXRCore 3.1.x chooses specialised interleaving unpackers from the output pointers and
   some of them return channels in the wrong order (see exr_read.c's io_read_exr); the decompressed layout is fixed
   by the format (per line, per channel in file order, `width` little-endian values), so convert it here. */
typedef struct unpack_target {
    float *out;
    int width, count;   /* output row length in pixels, values per pixel */
    int x0, y0;         /* chunk origin in the data window */
    int row0, rows;     /* the rows of the data window `out` holds (out's row 0 is row0) */
    const int *slot_of; /* [count]: the decoder channel feeding output slot k */
    struct libdeflate_decompressor *inflater; /* ZIP / ZIPS chunks: libdeflate instead of the library's zlib */
    unsigned char *scratch;                   /* the inflated, still predicted bytes (unpacked size) */
    size_t scratch_size;
} unpack_target;

/* The decompress step of a ZIP / ZIPS chunk: libdeflate (issue 28: zlib's inflate was a fifth of a composite's CPU). */
static exr_result_t inflate_zip(exr_decode_pipeline_t *dec)
{
    const unpack_target *t = (const unpack_target *)dec->decoding_user_data;
    if (!t) return EXR_ERR_INVALID_ARGUMENT;
    return io_exr_inflate_chunk(dec, t->inflater, t->scratch, t->scratch_size);
}

/* 1 unless VKSKY_EXR_ZLIB_INFLATE=1 asks for OpenEXRCore's own inflate (tests compare the two). */
static int use_libdeflate(void)
{
    const char *v = getenv("VKSKY_EXR_ZLIB_INFLATE");
    return !(v && v[0] && v[0] != '0');
}

static float load_value(const uint8_t *s, int type)
{
    if (type == EXR_PIXEL_HALF) {
        uint16_t h = (uint16_t)(s[0] | (s[1] << 8));
        uint32_t sign = (uint32_t)(h >> 15) << 31, e = (h >> 10) & 0x1f, m = h & 0x3ff, bits;
        if (e == 0x1f) {
            bits = sign | 0x7f800000u | (m << 13);
        } else if (e != 0) {
            bits = sign | ((e + 112u) << 23) | (m << 13);
        } else if (m == 0) {
            bits = sign;
        } else { /* subnormal half: exact in float */
            float f = (float)m * (1.0f / 16777216.0f);
            return sign ? -f : f;
        }
        float f;
        memcpy(&f, &bits, sizeof f);
        return f;
    }
    uint32_t u = (uint32_t)s[0] | ((uint32_t)s[1] << 8) | ((uint32_t)s[2] << 16) | ((uint32_t)s[3] << 24);
    if (type == EXR_PIXEL_UINT) return (float)u;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static exr_result_t unpack_to_float(exr_decode_pipeline_t *dec)
{
    const unpack_target *t = (const unpack_target *)dec->decoding_user_data;
    const uint8_t *src = (const uint8_t *)dec->unpacked_buffer;
    uint64_t avail = dec->chunk.unpacked_size, pos = 0;
    if (!t || !src) return EXR_ERR_CORRUPT_CHUNK;
    for (int ly = 0; ly < dec->chunk.height; ++ly) {
        int row = t->y0 + ly - t->row0;   /* a row outside the band is decoded (it is in the chunk), not stored */
        for (int c = 0; c < dec->channel_count; ++c) {
            const exr_coding_channel_info_t *ci = &dec->channels[c];
            /* A subsampled channel (never one we read: refused up front) has ci->width values on every
               y_samples-th line of the image only. */
            if (ci->y_samples > 1 && (dec->chunk.start_y + ly) % ci->y_samples != 0) continue;
            if (ci->width < 0 || ci->width > dec->chunk.width) return EXR_ERR_CORRUPT_CHUNK;
            int bpe = ci->bytes_per_element;
            if (bpe != (ci->data_type == EXR_PIXEL_HALF ? 2 : 4)) return EXR_ERR_CORRUPT_CHUNK;
            uint64_t nbytes = (uint64_t)ci->width * (uint64_t)bpe;
            if (pos + nbytes > avail) return EXR_ERR_CORRUPT_CHUNK;
            for (int k = 0; k < t->count && row >= 0 && row < t->rows; ++k) {
                if (t->slot_of[k] != c) continue;
                if (ci->width != dec->chunk.width || ci->height != dec->chunk.height) return EXR_ERR_CORRUPT_CHUNK;
                const uint8_t *s = src + pos;
                float *dst = t->out + ((size_t)row * (size_t)t->width + (size_t)t->x0) * (size_t)t->count +
                             (size_t)k;
                for (int x = 0; x < ci->width; ++x, s += bpe) dst[(size_t)x * (size_t)t->count] = load_value(s, ci->data_type);
            }
            pos += nbytes;
        }
    }
    return EXR_ERR_SUCCESS;
}

static const char *compression_name(exr_compression_t c)
{
    static const char *names[] = {"NONE", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
    return (unsigned)c < sizeof names / sizeof names[0] ? names[c] : "unknown";
}

/* Decodes one chunk into `out` (slot_of[k] = channel index in the part, or -1). */
static int read_chunk(exr_context_t ctxt, const io_exr_src *src, int part, const exr_chunk_info_t *cinfo, int x0,
                      int y0, float *out, int width, int row0, int rows, int count, const int *want, char *err,
                      size_t err_size)
{
    if (cinfo->data_offset > src->size || cinfo->packed_size > src->size - cinfo->data_offset) {
        io_exr_read_err(err, err_size, src,
                        "truncated chunk in part %d at rows %d-%d: its %llu bytes at offset %llu run past the file's end "
                        "(%llu bytes)",
                        part, y0, y0 + cinfo->height - 1, (unsigned long long)cinfo->packed_size,
                        (unsigned long long)cinfo->data_offset, (unsigned long long)src->size);
        return -1;
    }
    if (cinfo->unpacked_size > IO_EXR_READ_MAX_CHUNK_BYTES) {
        io_exr_read_err(err, err_size, src, "a chunk of part %d would decompress to %llu bytes; at most %llu accepted",
                        part, (unsigned long long)cinfo->unpacked_size,
                        (unsigned long long)IO_EXR_READ_MAX_CHUNK_BYTES);
        return -1;
    }
    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    exr_result_t rc = exr_decoding_initialize(ctxt, part, cinfo, &dec);
    int slot_of[64];
    int *slots = count <= 64 ? slot_of : (int *)malloc((size_t)count * sizeof(int));
    if (rc == EXR_ERR_SUCCESS && !slots) rc = EXR_ERR_OUT_OF_MEMORY;
    if (rc == EXR_ERR_SUCCESS) {
        for (int k = 0; k < count; ++k) slots[k] = -1;
        /* The library picks its read and decompress stages only for channels with an output pointer; ours is a
           placeholder inside `out` (never written through: the unpack stage is ours). */
        for (int c = 0; c < dec.channel_count; ++c) {
            exr_coding_channel_info_t *ci = &dec.channels[c];
            ci->decode_to_ptr = NULL;
            for (int k = 0; k < count; ++k) {
                if (want[k] != c) continue;
                slots[k] = c;
                ci->decode_to_ptr = (uint8_t *)out;
                ci->user_pixel_stride = count * (int32_t)sizeof(float);
                ci->user_line_stride = width * count * (int32_t)sizeof(float);
                ci->user_data_type = EXR_PIXEL_FLOAT;
                ci->user_bytes_per_element = (int16_t)sizeof(float);
            }
        }
        unpack_target target = {out, width, count, x0, y0, row0, rows, slots, NULL, NULL, 0};
        rc = exr_decoding_choose_default_routines(ctxt, part, &dec);
        int zip = cinfo->compression == EXR_COMPRESSION_ZIP || cinfo->compression == EXR_COMPRESSION_ZIPS;
        if (rc == EXR_ERR_SUCCESS && zip && dec.decompress_fn && use_libdeflate() &&
            cinfo->packed_size != cinfo->unpacked_size) {
            target.inflater = libdeflate_alloc_decompressor();
            target.scratch_size = (size_t)cinfo->unpacked_size;
            target.scratch = (unsigned char *)malloc(target.scratch_size ? target.scratch_size : 1);
            if (!target.inflater || !target.scratch) rc = EXR_ERR_OUT_OF_MEMORY;
            dec.decompress_fn = inflate_zip;
        }
        if (rc == EXR_ERR_SUCCESS) {
            dec.decoding_user_data = &target;
            dec.unpack_and_convert_fn = unpack_to_float;
            rc = exr_decoding_run(ctxt, part, &dec);
        }
        if (target.inflater) libdeflate_free_decompressor(target.inflater);
        free(target.scratch);
    }
    exr_decoding_destroy(ctxt, &dec);
    if (slots != slot_of) free(slots);
    if (rc == EXR_ERR_SUCCESS) return 0;
    exr_compression_t comp = EXR_COMPRESSION_NONE;
    exr_get_compression(ctxt, part, &comp);
    if (comp == EXR_COMPRESSION_DWAA || comp == EXR_COMPRESSION_DWAB) {
        io_exr_read_err(err, err_size, src,
                        "part %d is %s-compressed, which OpenEXR 3.1's C library cannot decode (%s); re-save it with "
                        "ZIP, PIZ or another lossless compression",
                        part, compression_name(comp), io_exr_read_msg(rc));
    } else {
        io_exr_read_err(err, err_size, src, "corrupt %s-compressed chunk in part %d at rows %d-%d: %s",
                        compression_name(comp), part, y0, y0 + cinfo->height - 1, io_exr_read_msg(rc));
    }
    return -1;
}

/* Reads every wanted channel of `part` (want[k] = its index in the part's channel list, or -1), rows [row0, row0 +
   rows) of it: only the chunks that hold them. */
typedef struct part_job {
    exr_context_t ctxt;
    const io_exr_src *src;
    int part;
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    int step_x, step_y, nx, cy0;
    int width, height, row0, rows;
    float *out;
    int count;
    const int *want;
} part_job;

/* Chunk `idx` of the band (row-major over its chunk rows); 0, or -1 + err. Safe on worker threads: OpenEXRCore
   reads a context from several threads, the file source reads with pread, and chunks write disjoint pixels. */
static int part_chunk(const part_job *j, int idx, char *err, size_t err_size)
{
    exr_context_t ctxt = j->ctxt;
    const io_exr_src *src = j->src;
    int part = j->part, width = j->width, height = j->height, row0 = j->row0, rows = j->rows, count = j->count;
    exr_storage_t storage = j->storage;
    exr_attr_box2i_t dw = j->dw;
    float *out = j->out;
    const int *want = j->want;
    int cx = idx % j->nx, cy = j->cy0 + idx / j->nx, step_x = j->step_x, step_y = j->step_y;
    exr_chunk_info_t cinfo;
    memset(&cinfo, 0, sizeof cinfo);
    exr_result_t rc;
    int x0 = cx * step_x, y0 = cy * step_y;
    if (storage == EXR_STORAGE_SCANLINE)
        rc = exr_read_scanline_chunk_info(ctxt, part, dw.min.y + y0, &cinfo);
    else
        rc = exr_read_tile_chunk_info(ctxt, part, cx, cy, 0, 0, &cinfo);
    if (rc != EXR_ERR_SUCCESS) {
        exr_compression_t comp = EXR_COMPRESSION_NONE;
        exr_get_compression(ctxt, part, &comp);
        /* 3.1's C library refuses a chunk whose packed size exceeds its unpacked size; B44 pads HALF data to
           4x4 blocks, so a small edge tile of a valid file can be refused (the C++ library reads it). */
        int b44 = comp == EXR_COMPRESSION_B44 || comp == EXR_COMPRESSION_B44A;
        io_exr_read_err(err, err_size, src, "truncated or corrupt chunk in part %d at rows from %d: %s%s", part,
                        y0, io_exr_read_msg(rc),
                        b44 ? " (OpenEXR 3.1's C library refuses some valid B44 edge tiles: re-save with ZIP "
                              "or PIZ if other programs read this file)"
                            : "");
        return -1;
    }
    if (storage == EXR_STORAGE_SCANLINE) { /* scanline chunks state their own rows */
        x0 = cinfo.start_x - dw.min.x;
        y0 = cinfo.start_y - dw.min.y;
    }
    if (x0 < 0 || y0 < 0 || cinfo.width <= 0 || cinfo.height <= 0 || cinfo.width > width - x0 ||
        cinfo.height > height - y0) {
        io_exr_read_err(err, err_size, src, "corrupt chunk in part %d: %dx%d at (%d, %d) outside the %dx%d "
                        "data window", part, cinfo.width, cinfo.height, x0, y0, width, height);
        return -1;
    }
    if (read_chunk(ctxt, src, part, &cinfo, x0, y0, out, width, row0, rows, count, want, err, err_size) != 0)
        return -1;
    return 0;
}

/* The band's chunks decoded by worker threads (issue 28: inflate was a fifth of a composite's CPU). Each worker
   takes the next chunk index; the error reported is the first failing chunk's in file order, so the outcome does not
   depend on the thread count. */
typedef struct chunk_pool {
    const part_job *job;
    int total;
    atomic_int next;
    pthread_mutex_t lock;
    int failed_at; /* lowest failing index, total when none */
    char err[512];
} chunk_pool;

static void *chunk_worker(void *arg)
{
    chunk_pool *p = (chunk_pool *)arg;
    char err[512];
    for (;;) {
        int idx = atomic_fetch_add(&p->next, 1);
        if (idx >= p->total) break;
        pthread_mutex_lock(&p->lock);
        int stop = idx > p->failed_at;
        pthread_mutex_unlock(&p->lock);
        if (stop) break;
        if (part_chunk(p->job, idx, err, sizeof err) != 0) {
            pthread_mutex_lock(&p->lock);
            if (idx < p->failed_at) {
                p->failed_at = idx;
                memcpy(p->err, err, sizeof err);
            }
            pthread_mutex_unlock(&p->lock);
            break;
        }
    }
    return NULL;
}

static int run_chunks(const part_job *job, int total, char *err, size_t err_size)
{
    int threads = io_encode_threads();
    if (threads > 16) threads = 16;
    if (threads > total) threads = total;
    if (threads <= 1) {
        for (int i = 0; i < total; ++i)
            if (part_chunk(job, i, err, err_size) != 0) return -1;
        return 0;
    }
    chunk_pool p;
    memset(&p, 0, sizeof p);
    p.job = job, p.total = total, p.failed_at = total;
    atomic_init(&p.next, 0);
    pthread_mutex_init(&p.lock, NULL);
    pthread_t tid[16];
    int started = 0;
    for (; started < threads - 1; ++started)
        if (pthread_create(&tid[started], NULL, chunk_worker, &p) != 0) break;
    chunk_worker(&p); /* the caller works too; with no worker started it does every chunk */
    for (int i = 0; i < started; ++i) pthread_join(tid[i], NULL);
    pthread_mutex_destroy(&p.lock);
    if (p.failed_at < total) {
        snprintf(err, err_size, "%s", p.err);
        return -1;
    }
    return 0;
}

static int read_part(exr_context_t ctxt, const io_exr_src *src, int part, int width, int height, int row0, int rows,
                     float *out, int count, const int *want, char *err, size_t err_size)
{
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    int32_t chunks = 0;
    if (exr_get_storage(ctxt, part, &storage) != EXR_ERR_SUCCESS || exr_get_data_window(ctxt, part, &dw) ||
        exr_get_chunk_count(ctxt, part, &chunks) != EXR_ERR_SUCCESS || chunks <= 0) {
        io_exr_read_err(err, err_size, src, "part %d: incomplete header (%s)", part, io_exr_read_msg(EXR_ERR_SUCCESS));
        return -1;
    }
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
        io_exr_read_err(err, err_size, src, "part %d holds deep data; only flat scanline and tiled parts are read", part);
        return -1;
    }
    /* The chunk table (8 bytes a chunk) must fit in the file before the library allocates it. */
    if ((uint64_t)chunks * 8u > src->size) {
        io_exr_read_err(err, err_size, src, "truncated: part %d's chunk table needs %lld bytes, the file has %llu",
                        part, (long long)chunks * 8, (unsigned long long)src->size);
        return -1;
    }
    int32_t step_x = width, step_y = 0;
    if (storage == EXR_STORAGE_SCANLINE) {
        if (exr_get_scanlines_per_chunk(ctxt, part, &step_y) != EXR_ERR_SUCCESS) step_y = 0;
    } else {
        uint32_t tx = 0, ty = 0;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        if (exr_get_tile_descriptor(ctxt, part, &tx, &ty, &lm, &rm) == EXR_ERR_SUCCESS && tx > 0 && ty > 0 &&
            tx <= IO_EXR_READ_MAX_SIDE && ty <= IO_EXR_READ_MAX_SIDE) {
            step_x = (int32_t)tx;
            step_y = (int32_t)ty;
        }
    }
    if (step_x <= 0 || step_y <= 0) {
        io_exr_read_err(err, err_size, src, "part %d: invalid %s", part,
                        storage == EXR_STORAGE_SCANLINE ? "compression (no scanlines per chunk)" : "tile size");
        return -1;
    }
    int nx = (width + step_x - 1) / step_x, ny = (height + step_y - 1) / step_y;
    /* Chunk row cy holds rows [cy step_y, (cy + 1) step_y) (scanline chunks say so again): the band's chunk rows. */
    int cy0 = row0 / step_y, cy1 = (int)(((int64_t)row0 + rows + step_y - 1) / step_y);
    if (cy1 > ny) cy1 = ny;
    part_job job = {ctxt, src, part, storage, dw, step_x, step_y, nx, cy0, width, height, row0, rows, out, count, want};
    return run_chunks(&job, (cy1 - cy0) * nx, err, err_size);
}

/* "R, G, B, ViewLayer.Combined.R, ..." (cut short) for the missing-channel message. */
static void list_channels(exr_context_t ctxt, int nparts, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int p = 0; p < nparts; ++p) {
        const exr_attr_chlist_t *chl = NULL;
        if (exr_get_channels(ctxt, p, &chl) != EXR_ERR_SUCCESS || !chl) continue;
        for (int i = 0; i < chl->num_channels; ++i) {
            const char *n = chl->entries[i].name.str ? chl->entries[i].name.str : "";
            int w = snprintf(buf + len, size - len, "%s%s", len ? ", " : "", n);
            if (w < 0 || (size_t)w >= size - len) {
                if (size > 4) strcpy(buf + size - 4, "...");
                return;
            }
            len += (size_t)w;
        }
    }
}

int io_exr_read_channels_src(const io_exr_src *src, const char *const *names, int count, float *out, char *err,
                             size_t err_size)
{
    return io_exr_read_rows_src(src, names, count, 0, -1, out, err, err_size);
}

int io_exr_read_rows_src(const io_exr_src *src, const char *const *names, int count, int row0, int rows, float *out,
                         char *err, size_t err_size)
{
    if (!names || count <= 0 || count > 4096 || !out) {
        io_exr_read_err(err, err_size, src, "nothing to read (need 1 to 4096 channel names and an output buffer)");
        return -1;
    }
    exr_context_t ctxt = NULL;
    if (io_exr_src_start(src, &ctxt, err, err_size) != 0) return -1;
    int r = -1, nparts = 0, width = 0, height = 0;
    int *part_of = (int *)malloc((size_t)count * 2 * sizeof(int)), *want = part_of ? part_of + count : NULL;
    if (!part_of) {
        io_exr_read_err(err, err_size, src, "out of memory");
        goto done;
    }
    if (exr_get_count(ctxt, &nparts) != EXR_ERR_SUCCESS || nparts <= 0) {
        io_exr_read_err(err, err_size, src, "no parts in the file");
        goto done;
    }
    if (io_exr_part_size(ctxt, src, 0, &width, &height, err, err_size) != 0) goto done;
    if (rows < 0) row0 = 0, rows = height;   /* the whole data window */
    if (row0 < 0 || rows <= 0 || row0 > height - rows) {
        io_exr_read_err(err, err_size, src, "rows %d to %d are outside the %d rows of the image", row0,
                        row0 + rows - 1, height);
        goto done;
    }
    for (int k = 0; k < count; ++k) {
        part_of[k] = -1;
        for (int p = 0; p < nparts && part_of[k] < 0; ++p) {
            const exr_attr_chlist_t *chl = NULL;
            if (exr_get_channels(ctxt, p, &chl) != EXR_ERR_SUCCESS || !chl) continue;
            for (int i = 0; i < chl->num_channels; ++i) {
                const exr_attr_chlist_entry_t *e = &chl->entries[i];
                if (!names[k] || !e->name.str || strcmp(names[k], e->name.str) != 0) continue;
                if (e->x_sampling != 1 || e->y_sampling != 1) {
                    io_exr_read_err(err, err_size, src, "channel '%s' is subsampled (%dx%d); only full-resolution "
                                    "channels are read", names[k], e->x_sampling, e->y_sampling);
                    goto done;
                }
                if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT &&
                    e->pixel_type != EXR_PIXEL_UINT) {
                    io_exr_read_err(err, err_size, src, "channel '%s' has unknown pixel type %d", names[k],
                                    (int)e->pixel_type);
                    goto done;
                }
                part_of[k] = p;
                want[k] = i;
                break;
            }
        }
        if (part_of[k] < 0) {
            char have[200];
            list_channels(ctxt, nparts, have, sizeof have);
            io_exr_read_err(err, err_size, src, "no channel '%.100s' (the file has: %s)", names[k] ? names[k] : "(null)",
                            have);
            goto done;
        }
    }
    for (int p = 0; p < nparts; ++p) {
        int used = 0;
        for (int k = 0; k < count; ++k) used |= part_of[k] == p;
        if (!used) continue;
        int pw = 0, ph = 0;
        if (io_exr_part_size(ctxt, src, p, &pw, &ph, err, err_size) != 0) goto done;
        if (pw != width || ph != height) {
            io_exr_read_err(err, err_size, src, "mismatched part sizes: part %d is %dx%d, part 0 is %dx%d; the parts "
                            "read must all be the size of part 0", p, pw, ph, width, height);
            goto done;
        }
        int wantp[4096];
        for (int k = 0; k < count; ++k) wantp[k] = part_of[k] == p ? want[k] : -1;
        if (read_part(ctxt, src, p, width, height, row0, rows, out, count, wantp, err, err_size) != 0) goto done;
    }
    r = 0;
done:
    free(part_of);
    exr_finish(&ctxt);
    return r;
}

int io_exr_read_channels(const char *path, const char *const *names, int count, float *out, char *err,
                         size_t err_size)
{
    io_exr_src src;
    if (io_exr_src_open_file(&src, path, err, err_size) != 0) return -1;
    int r = io_exr_read_channels_src(&src, names, count, out, err, err_size);
    io_exr_src_close(&src);
    return r;
}

int io_exr_read_rows(const char *path, const char *const *names, int count, int row0, int rows, float *out, char *err,
                     size_t err_size)
{
    io_exr_src src;
    if (io_exr_src_open_file(&src, path, err, err_size) != 0) return -1;
    int r = io_exr_read_rows_src(&src, names, count, row0, rows, out, err, err_size);
    io_exr_src_close(&src);
    return r;
}
