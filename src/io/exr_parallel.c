/* vksky image I/O: EXR chunks compressed on worker threads, written in order (exr_parallel.h).
 *
 * OpenEXRCore's chunk API splits a chunk's encoding into steps: exr_encoding_initialize (the chunk's channels),
 * exr_encoding_run (pack the channels under the library's lock, then compress_fn, then the write callback) and
 * exr_write_scanline_chunk (the bytes into the file at the next offset). A scanline file's chunks are written in
 * increasing y here (the same bytes for any thread count), so the workers run initialize + run with the write step
 * left out (write_fn NULL), and a finished chunk is written once every chunk before it is. The context is shared:
 * every call that touches its state outside exr_encoding_run is made under our mutex.
 *
 * The compress step is ours (chunk_compress): it first marks the chunk packed -- the library has copied its rows
 * out, so the caller's rows are free again; io_exr_pool_chunks waits for exactly that -- and then compresses ZIP and
 * ZIPS through libdeflate (exr_deflate.h; a compressor per worker), the rest through the library's own step. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/exr_parallel.h"
#include "io/exr_common.h"
#include "io/exr_deflate.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

typedef struct chunk_slot chunk_slot;

/* A chunk's compress step's view (enc->encoding_user_data); wrap first: io_exr_compress_no_expand reads it. */
typedef struct chunk_hook {
    io_exr_compress_wrap wrap;
    io_exr_pool *pool;
    chunk_slot *slot;
    struct libdeflate_compressor *deflate;   /* ZIP / ZIPS: this thread's compressor */
} chunk_hook;

struct chunk_slot {
    exr_encode_pipeline_t enc;
    chunk_hook hook;
    exr_result_t rc;
    bool packed;   /* its rows are copied out (or it failed before): the caller's rows are no longer read */
    bool done;     /* compressed (or failed): waits to be written */
};

struct io_exr_pool {
    exr_context_t ctxt;
    int part, lpc, threads, window;
    bool zip;                /* ZIP or ZIPS: libdeflate at `zip_level` */
    int zip_level;
    struct libdeflate_compressor *own_deflate;   /* the caller's, with no worker */
    pthread_mutex_t lock;
    pthread_cond_t changed;  /* a chunk was packed, finished or written, or chunks were handed over */
    pthread_t *tids;
    int started;
    /* Chunks are numbered in the order they were handed over, over every call; chunk i uses slots[i % window]. */
    int queued, next, written;
    int unpacked;            /* claimed, not yet packed */
    int band_first, band_y0; /* the call being fed: its first chunk and that chunk's row */
    io_exr_feed_fn feed;
    void *user;
    exr_result_t rc;         /* the first failure */
    bool failed, closing;
    chunk_slot *slots;
};

static void *pool_alloc(exr_transcoding_pipeline_buffer_id_t id, size_t n) { (void)id; return malloc(n); }
static void pool_free(exr_transcoding_pipeline_buffer_id_t id, void *p) { (void)id; free(p); }

static void mark_packed(io_exr_pool *p, chunk_slot *s)
{
    pthread_mutex_lock(&p->lock);
    if (!s->packed) {
        s->packed = true, --p->unpacked;
        pthread_cond_broadcast(&p->changed);
    }
    pthread_mutex_unlock(&p->lock);
}

static exr_result_t chunk_compress(exr_encode_pipeline_t *enc)
{
    chunk_hook *h = enc->encoding_user_data;
    mark_packed(h->pool, h->slot);
    return h->deflate ? io_exr_deflate_chunk(enc, h->deflate) : io_exr_compress_no_expand(enc);
}

/* Chunk i, under the lock: its info, channels and rows, and our compress step. */
static exr_result_t prepare(io_exr_pool *p, int i, chunk_slot *s, struct libdeflate_compressor *deflate)
{
    int y = p->band_y0 + (i - p->band_first) * p->lpc;
    exr_chunk_info_t cinfo;
    memset(&cinfo, 0, sizeof cinfo);
    memset(&s->enc, 0, sizeof s->enc);
    s->packed = s->done = false;
    ++p->unpacked;
    exr_result_t rc = exr_write_scanline_chunk_info(p->ctxt, p->part, y, &cinfo);
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_initialize(p->ctxt, p->part, &cinfo, &s->enc);
    if (rc == EXR_ERR_SUCCESS) rc = p->feed(p->user, &s->enc, cinfo.start_y, cinfo.height);
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_choose_default_routines(p->ctxt, p->part, &s->enc);
    if (rc != EXR_ERR_SUCCESS) return rc;
    s->enc.alloc_fn = pool_alloc, s->enc.free_fn = pool_free;
    if (s->enc.compress_fn) {
        s->hook = (chunk_hook){{s->enc.compress_fn}, p, s, p->zip ? deflate : NULL};
        s->enc.encoding_user_data = &s->hook;
        s->enc.compress_fn = chunk_compress;
    }
    /* No yield or write here: chunks are written in order (write_ready). */
    s->enc.yield_until_ready_fn = NULL;
    s->enc.write_fn = NULL;
    return EXR_ERR_SUCCESS;
}

/* Outside the lock: pack and compress (the expensive part). */
static exr_result_t compress(io_exr_pool *p, chunk_slot *s)
{
    exr_result_t rc = exr_encoding_run(p->ctxt, p->part, &s->enc);
    s->enc.encoding_user_data = NULL;
    return rc;
}

static void fail(io_exr_pool *p, exr_result_t rc)
{
    if (!p->failed) p->failed = true, p->rc = rc;
}

/* Under the lock: chunk s finished; then every finished chunk next in order is written. */
static void finish(io_exr_pool *p, chunk_slot *s, exr_result_t rc)
{
    if (!s->packed) s->packed = true, --p->unpacked;   /* no compress step (none), or failed before it */
    s->rc = rc, s->done = true;
    while (!p->failed && p->written < p->queued && p->slots[p->written % p->window].done) {
        chunk_slot *w = &p->slots[p->written % p->window];
        exr_result_t wrc = w->rc;
        if (wrc == EXR_ERR_SUCCESS)
            wrc = exr_write_scanline_chunk(p->ctxt, p->part, w->enc.chunk.start_y, w->enc.compressed_buffer,
                                           w->enc.compressed_bytes);
        exr_encoding_destroy(p->ctxt, &w->enc);
        w->done = false;
        if (wrc != EXR_ERR_SUCCESS) fail(p, wrc);
        else ++p->written;
    }
    pthread_cond_broadcast(&p->changed);
}

static void *worker(void *arg)
{
    io_exr_pool *p = arg;
    struct libdeflate_compressor *deflate = p->zip ? io_exr_deflate_alloc(p->zip_level) : NULL;
    pthread_mutex_lock(&p->lock);
    if (p->zip && !deflate) fail(p, EXR_ERR_OUT_OF_MEMORY), pthread_cond_broadcast(&p->changed);
    for (;;) {
        /* The next chunk once it is handed over and its slot is free (the chunk `window` before it is written). */
        while (!p->failed && !p->closing && !(p->next < p->queued && p->next < p->written + p->window))
            pthread_cond_wait(&p->changed, &p->lock);
        if (p->failed || p->closing) break;
        int i = p->next++;
        chunk_slot *s = &p->slots[i % p->window];
        exr_result_t rc = prepare(p, i, s, deflate);
        pthread_mutex_unlock(&p->lock);
        if (rc == EXR_ERR_SUCCESS) rc = compress(p, s);
        pthread_mutex_lock(&p->lock);
        finish(p, s, rc);
    }
    pthread_mutex_unlock(&p->lock);
    io_exr_deflate_free(deflate);
    return NULL;
}

io_exr_pool *io_exr_pool_create(exr_context_t ctxt, int part, int lines_per_chunk, int threads)
{
    io_exr_pool *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    *p = (io_exr_pool){.ctxt = ctxt, .part = part, .lpc = lines_per_chunk, .threads = threads > 1 ? threads : 1};
    exr_compression_t comp = EXR_COMPRESSION_NONE;
    p->zip_level = -1;
    if (exr_get_compression(ctxt, part, &comp) == EXR_ERR_SUCCESS &&
        (comp == EXR_COMPRESSION_ZIP || comp == EXR_COMPRESSION_ZIPS))
        p->zip = exr_get_zip_compression_level(ctxt, part, &p->zip_level) == EXR_ERR_SUCCESS;
    /* Two finished chunks per worker may wait to be written: enough to keep every worker busy while one chunk is
     * written, few enough that a wide band's chunks are never all in memory at once. */
    p->window = p->threads > 1 ? 2 * p->threads : 1;
    p->slots = calloc((size_t)p->window, sizeof *p->slots);
    if (p->threads > 1) p->tids = calloc((size_t)p->threads, sizeof *p->tids);
    else if (p->zip) p->own_deflate = io_exr_deflate_alloc(p->zip_level);
    if (!p->slots || (p->threads > 1 ? !p->tids : p->zip && !p->own_deflate)) {
        io_exr_deflate_free(p->own_deflate);
        free(p->slots), free(p->tids), free(p);
        return NULL;
    }
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->changed, NULL);
    if (p->threads > 1) {
        for (; p->started < p->threads; ++p->started)
            if (pthread_create(&p->tids[p->started], NULL, worker, p) != 0) break;
        if (p->started == 0) {
            io_exr_pool_destroy(p);
            return NULL;
        }
    }
    return p;
}

exr_result_t io_exr_pool_chunks(io_exr_pool *p, int y0, int count, io_exr_feed_fn feed, void *user)
{
    pthread_mutex_lock(&p->lock);
    if (!p->failed && count > 0) {
        p->band_first = p->queued, p->band_y0 = y0, p->feed = feed, p->user = user;
        p->queued += count;
        if (p->threads <= 1) {
            /* No worker: each chunk encoded and written in turn, here. */
            while (!p->failed && p->next < p->queued) {
                chunk_slot *s = &p->slots[0];
                exr_result_t rc = prepare(p, p->next++, s, p->own_deflate);
                pthread_mutex_unlock(&p->lock);
                if (rc == EXR_ERR_SUCCESS) rc = compress(p, s);
                pthread_mutex_lock(&p->lock);
                finish(p, s, rc);
            }
        }
        pthread_cond_broadcast(&p->changed);
        /* Until no chunk of this call is left to claim and none claimed still reads the rows (after a failure too:
         * a worker may be packing one). */
        while ((!p->failed && p->next < p->queued) || p->unpacked > 0) pthread_cond_wait(&p->changed, &p->lock);
        p->feed = NULL, p->user = NULL;
    }
    exr_result_t rc = p->failed ? p->rc : EXR_ERR_SUCCESS;
    pthread_mutex_unlock(&p->lock);
    return rc;
}

exr_result_t io_exr_pool_drain(io_exr_pool *p)
{
    pthread_mutex_lock(&p->lock);
    while (!p->failed && p->written < p->queued) pthread_cond_wait(&p->changed, &p->lock);
    exr_result_t rc = p->failed ? p->rc : EXR_ERR_SUCCESS;
    pthread_mutex_unlock(&p->lock);
    return rc;
}

void io_exr_pool_destroy(io_exr_pool *p)
{
    if (!p) return;
    pthread_mutex_lock(&p->lock);
    p->closing = true;
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
    for (int t = 0; t < p->started; ++t) pthread_join(p->tids[t], NULL);
    /* Chunks compressed but never written (a failure, or a file given up). */
    for (int k = 0; k < p->window; ++k)
        if (p->slots[k].done) exr_encoding_destroy(p->ctxt, &p->slots[k].enc);
    io_exr_deflate_free(p->own_deflate);
    pthread_cond_destroy(&p->changed);
    pthread_mutex_destroy(&p->lock);
    free(p->slots), free(p->tids), free(p);
}

exr_result_t io_exr_encode_chunks(exr_context_t ctxt, int part, int y0, int count, int lines_per_chunk,
                                  io_exr_feed_fn feed, void *user, int threads)
{
    io_exr_pool *p = io_exr_pool_create(ctxt, part, lines_per_chunk, threads < count ? threads : count);
    if (!p) return EXR_ERR_OUT_OF_MEMORY;
    exr_result_t rc = io_exr_pool_chunks(p, y0, count, feed, user);
    if (rc == EXR_ERR_SUCCESS) rc = io_exr_pool_drain(p);
    io_exr_pool_destroy(p);
    return rc;
}
