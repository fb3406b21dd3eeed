/* vksky image I/O: a PNG's IDAT deflated in blocks on worker threads (png_parallel.h says why by hand). A batch of
 * rows goes through two passes, each over the batch's blocks with every thread claiming the next block: filter the
 * rows (libpng's heuristic), then deflate each block with the 32 KiB before it as its dictionary. The calling thread
 * then writes the blocks in order, one IDAT chunk each. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/png_parallel.h"

#include <errno.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

enum {
    BLOCK_BYTES = 256 * 1024,   /* filtered bytes a block holds at least (one row when rows are longer) */
    WINDOW = 32768,             /* deflate's window: the dictionary a block starts from */
    MAX_THREADS = 64,
    BATCH_BLOCKS_PER_THREAD = 4 /* a batch: enough blocks to keep every thread busy, bounded memory */
};

struct io_png_par {
    FILE *fp;
    int width, height, threads, block_rows;
    size_t rowbytes;                    /* width * 4; a filtered row has one more byte (its filter type) */
    int next_row;                       /* rows handed over */
    int done_rows;                      /* rows compressed and written */
    uint8_t *pending;                   /* fewer than block_rows rows waiting for the rest of their block */
    int pending_rows;
    uint8_t *prev_row;                  /* the raw row before done_rows (zeros before the first) */
    uint8_t dict[WINDOW];               /* the last filtered bytes written: the next batch's first dictionary */
    size_t dict_len;
    uLong adler;                        /* Adler-32 of every filtered byte so far */
    int err_no;
    char msg[160];
};

typedef struct block {
    uint8_t *out;
    size_t out_len, in_len;
    uLong adler;
    int failed;
} block;

typedef struct batch {
    io_png_par *p;
    const uint8_t *raw;
    int rows, count;                    /* rows and blocks of this batch */
    bool last;                          /* it ends the image: its last block finishes the stream */
    uint8_t *filtered;
    block *blocks;
    int pass;                           /* 0: filter, 1: deflate */
    atomic_int next;
} batch;

static int fail(io_png_par *p, int err_no, const char *msg)
{
    p->err_no = err_no;
    snprintf(p->msg, sizeof p->msg, "%s", msg);
    return -1;
}

int io_png_par_wanted(int width, int height, int threads)
{
    if (threads < 2 || width < 1 || height < 1) return 0;
    size_t row = (size_t)width * 4u + 1u;
    size_t block_rows = row >= BLOCK_BYTES ? 1 : BLOCK_BYTES / row;
    return (size_t)height > block_rows;
}

io_png_par *io_png_par_create(FILE *fp, int width, int height, int threads)
{
    io_png_par *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    p->fp = fp, p->width = width, p->height = height;
    p->threads = threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : threads;
    p->rowbytes = (size_t)width * 4u;
    p->block_rows = p->rowbytes + 1 >= BLOCK_BYTES ? 1 : (int)(BLOCK_BYTES / (p->rowbytes + 1));
    p->pending = malloc((size_t)p->block_rows * p->rowbytes);
    p->prev_row = calloc(1, p->rowbytes);
    p->adler = adler32(0L, Z_NULL, 0);
    if (!p->pending || !p->prev_row) {
        io_png_par_free(p);
        return NULL;
    }
    return p;
}

static unsigned sum_abs(const uint8_t *f, size_t n, unsigned limit)
{
    unsigned s = 0;
    for (size_t i = 0; i < n && s <= limit; ++i) s += f[i] < 128 ? f[i] : 256u - f[i];
    return s;
}

static int paeth(int a, int b, int c)
{
    int pv = a + b - c, pa = abs(pv - a), pb = abs(pv - b), pc = abs(pv - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/* One row filtered with type t (1..4) into out (rowbytes bytes); up is the raw row above. 4 bytes a pixel. */
static void filter_as(int t, const uint8_t *x, const uint8_t *up, size_t n, uint8_t *out)
{
    for (size_t i = 0; i < n; ++i) {
        int a = i >= 4 ? x[i - 4] : 0, b = up[i], c = i >= 4 ? up[i - 4] : 0;
        int pred = t == 1 ? a : t == 2 ? b : t == 3 ? (a + b) >> 1 : paeth(a, b, c);
        out[i] = (uint8_t)(x[i] - pred);
    }
}

/* libpng's default choice (png_write_find_filter): the filter whose bytes, read as signed, have the smallest sum of
 * magnitudes; None first, a later one only when strictly smaller. `out` gets the type byte and the row. */
static void filter_row(const uint8_t *x, const uint8_t *up, size_t n, uint8_t *out, uint8_t *scratch)
{
    unsigned best = sum_abs(x, n, UINT32_MAX / 2);
    int best_type = 0;
    const uint8_t *best_bytes = x;
    for (int t = 1; t <= 4; ++t) {
        uint8_t *cand = scratch + (size_t)(t - 1) * n;
        filter_as(t, x, up, n, cand);
        unsigned s = sum_abs(cand, n, best);
        if (s < best) best = s, best_type = t, best_bytes = cand;
    }
    out[0] = (uint8_t)best_type;
    memcpy(out + 1, best_bytes, n);
}

static void filter_block(batch *b, int k)
{
    io_png_par *p = b->p;
    size_t rb = p->rowbytes;
    uint8_t *scratch = malloc(4 * rb);
    if (!scratch) {
        b->blocks[k].failed = 1;
        return;
    }
    int r0 = k * p->block_rows, r1 = r0 + p->block_rows < b->rows ? r0 + p->block_rows : b->rows;
    for (int r = r0; r < r1; ++r) {
        const uint8_t *up = r > 0 ? b->raw + (size_t)(r - 1) * rb : p->prev_row;
        filter_row(b->raw + (size_t)r * rb, up, rb, b->filtered + (size_t)r * (rb + 1), scratch);
    }
    free(scratch);
}

/* Deflates block k alone: raw deflate (the zlib header and trailer are written around the blocks), libpng's
 * settings (level 6, Z_FILTERED), the 32 KiB of filtered data before it as the dictionary, and a sync flush so the
 * next block starts on a byte boundary; the image's last block finishes the stream instead. */
static void deflate_block(batch *b, int k)
{
    io_png_par *p = b->p;
    block *blk = &b->blocks[k];
    if (blk->failed) return;
    size_t row = p->rowbytes + 1;
    const uint8_t *in = b->filtered + (size_t)k * (size_t)p->block_rows * row;
    int rows = b->rows - k * p->block_rows < p->block_rows ? b->rows - k * p->block_rows : p->block_rows;
    blk->in_len = (size_t)rows * row;
    blk->adler = adler32(adler32(0L, Z_NULL, 0), in, (uInt)blk->in_len);
    const uint8_t *dict = k > 0 ? in - WINDOW : p->dict;   /* a block before it holds > 32 KiB (BLOCK_BYTES) */
    size_t dict_len = k > 0 ? WINDOW : p->dict_len;
    z_stream z = {0};
    if (deflateInit2(&z, 6, Z_DEFLATED, -15, 8, Z_FILTERED) != Z_OK) {
        blk->failed = 1;
        return;
    }
    bool finish = b->last && k == b->count - 1;
    size_t cap = deflateBound(&z, (uLong)blk->in_len) + 64;   /* + the sync flush's empty stored block */
    blk->out = malloc(cap);
    if (!blk->out || (dict_len && deflateSetDictionary(&z, dict, (uInt)dict_len) != Z_OK)) {
        deflateEnd(&z);
        blk->failed = 1;
        return;
    }
    z.next_in = (Bytef *)in, z.avail_in = (uInt)blk->in_len;
    z.next_out = blk->out, z.avail_out = (uInt)cap;
    int rc = deflate(&z, finish ? Z_FINISH : Z_SYNC_FLUSH);
    blk->out_len = cap - z.avail_out;
    if ((finish ? rc != Z_STREAM_END : rc != Z_OK) || z.avail_in != 0) blk->failed = 1;
    deflateEnd(&z);
}

static void *worker(void *arg)
{
    batch *b = arg;
    for (int k; (k = atomic_fetch_add(&b->next, 1)) < b->count;) {
        if (b->pass == 0) filter_block(b, k);
        else deflate_block(b, k);
    }
    return NULL;
}

/* One pass over the batch's blocks on up to p->threads threads, the caller one of them (alone if none start). */
static void run_pass(batch *b, int pass)
{
    b->pass = pass;
    atomic_store(&b->next, 0);
    pthread_t t[MAX_THREADS];
    int started = 0;
    for (int i = 1; i < b->p->threads && i < b->count; ++i)
        if (pthread_create(&t[started], NULL, worker, b) == 0) ++started;
    worker(b);
    for (int i = 0; i < started; ++i) pthread_join(t[i], NULL);
}

static int put(io_png_par *p, const void *data, size_t n)
{
    if (n && fwrite(data, 1, n, p->fp) != n) return fail(p, errno ? errno : EIO, "write error");
    return 0;
}

static void be32(uint8_t *b, uint32_t v)
{
    b[0] = (uint8_t)(v >> 24), b[1] = (uint8_t)(v >> 16), b[2] = (uint8_t)(v >> 8), b[3] = (uint8_t)v;
}

/* One IDAT chunk: pre (the zlib header, on the first), the block's bytes, post (the Adler-32, on the last). */
static int write_idat(io_png_par *p, const uint8_t *pre, size_t npre, const uint8_t *data, size_t n,
                      const uint8_t *post, size_t npost)
{
    uint8_t head[8], crc[4];
    be32(head, (uint32_t)(npre + n + npost));
    memcpy(head + 4, "IDAT", 4);
    uLong c = crc32(0L, head + 4, 4);
    c = crc32(c, pre, (uInt)npre), c = crc32(c, data, (uInt)n), c = crc32(c, post, (uInt)npost);
    be32(crc, (uint32_t)c);
    return put(p, head, 8) || put(p, pre, npre) || put(p, data, n) || put(p, post, npost) || put(p, crc, 4) ? -1 : 0;
}

/* Compresses and writes `rows` rows starting at p->done_rows: a whole number of blocks, or the image's end. */
static int compress_batch(io_png_par *p, const uint8_t *raw, int rows)
{
    size_t row = p->rowbytes + 1;
    batch b = {.p = p, .raw = raw, .rows = rows, .count = (rows + p->block_rows - 1) / p->block_rows,
               .last = p->done_rows + rows == p->height};
    b.filtered = malloc((size_t)rows * row);
    b.blocks = calloc((size_t)b.count, sizeof *b.blocks);
    int rc = 0;
    if (!b.filtered || !b.blocks) {
        rc = fail(p, 0, "out of memory for the PNG's blocks");
        goto out;
    }
    run_pass(&b, 0);
    run_pass(&b, 1);
    for (int k = 0; k < b.count && rc == 0; ++k) {
        block *blk = &b.blocks[k];
        if (blk->failed) {
            rc = fail(p, 0, "zlib: cannot deflate a block (out of memory)");
            break;
        }
        /* The zlib header of a 32 KiB window at the default level (CMF 0x78, FLG 0x9c: no dictionary for the
         * decoder, the blocks' dictionaries are the stream's own earlier bytes). */
        static const uint8_t zhead[2] = {0x78, 0x9c};
        bool first = p->done_rows == 0 && k == 0, final = b.last && k == b.count - 1;
        p->adler = adler32_combine(p->adler, blk->adler, (z_off_t)blk->in_len);
        uint8_t trailer[4];
        be32(trailer, (uint32_t)p->adler);
        rc = write_idat(p, zhead, first ? 2 : 0, blk->out, blk->out_len, trailer, final ? 4 : 0);
    }
    if (rc == 0) {
        size_t total = (size_t)rows * row, keep = total < WINDOW ? total : WINDOW;
        if (keep < WINDOW && p->dict_len) {   /* not reached (a batch holds a block), kept correct anyway */
            size_t old = p->dict_len + keep > WINDOW ? WINDOW - keep : p->dict_len;
            memmove(p->dict, p->dict + p->dict_len - old, old);
            p->dict_len = old;
        } else {
            p->dict_len = 0;
        }
        memcpy(p->dict + p->dict_len, b.filtered + total - keep, keep);
        p->dict_len += keep;
        memcpy(p->prev_row, raw + (size_t)(rows - 1) * p->rowbytes, p->rowbytes);
        p->done_rows += rows;
    }
out:
    for (int k = 0; b.blocks && k < b.count; ++k) free(b.blocks[k].out);
    free(b.blocks);
    free(b.filtered);
    return rc;
}

int io_png_par_rows(io_png_par *p, const uint8_t *rgba8, int rows)
{
    if (rows < 0 || rows > p->height - p->next_row) return fail(p, 0, "more rows than the image has");
    int bl = p->block_rows, cap = bl * p->threads * BATCH_BLOCKS_PER_THREAD;
    while (rows > 0) {
        if (p->pending_rows == 0) {   /* whole blocks straight from the caller's rows */
            int n = rows / bl * bl;
            if (n > cap) n = cap;
            if (n == 0 && p->next_row + rows == p->height) n = rows;   /* the image's last, short block */
            if (n > 0) {
                p->next_row += n;
                if (compress_batch(p, rgba8, n)) return -1;
                rgba8 += (size_t)n * p->rowbytes, rows -= n;
                continue;
            }
        }
        int take = bl - p->pending_rows < rows ? bl - p->pending_rows : rows;
        memcpy(p->pending + (size_t)p->pending_rows * p->rowbytes, rgba8, (size_t)take * p->rowbytes);
        p->pending_rows += take, p->next_row += take;
        rgba8 += (size_t)take * p->rowbytes, rows -= take;
        if (p->pending_rows == bl || p->next_row == p->height) {
            int n = p->pending_rows;
            p->pending_rows = 0;
            if (compress_batch(p, p->pending, n)) return -1;
        }
    }
    return 0;
}

int io_png_par_finish(io_png_par *p)
{
    if (p->done_rows != p->height) return fail(p, 0, "fewer rows than the image has");
    static const uint8_t iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    return put(p, iend, sizeof iend);
}

int io_png_par_errno(const io_png_par *p) { return p->err_no; }
const char *io_png_par_message(const io_png_par *p) { return p->msg; }

void io_png_par_free(io_png_par *p)
{
    if (!p) return;
    free(p->pending);
    free(p->prev_row);
    free(p);
}
