/* vksky image I/O: EXR chunks compressed on worker threads, one writer (exr_parallel.h).
 *
 * OpenEXRCore's chunk API splits a chunk's encoding into steps: exr_encoding_initialize (the chunk's channels),
 * exr_encoding_run (pack the channels, compress, then the write callback) and exr_write_scanline_chunk (the bytes
 * into the file at the next offset). A scanline file's chunks must be written in increasing y, so the workers run
 * initialize + run with the write step left out (write_fn NULL), and the writer -- the calling thread -- writes each
 * finished chunk in order. The context is shared: every call that touches its state outside exr_encoding_run (which
 * takes the library's own lock while it packs) is made under our mutex. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/exr_parallel.h"
#include "io/exr_common.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

typedef struct chunk_slot {
    exr_encode_pipeline_t enc;
    exr_result_t rc;
    bool done;
} chunk_slot;

typedef struct encoder {
    exr_context_t ctxt;
    int part, y0, count, lpc, window;
    io_exr_feed_fn feed;
    void *user;
    pthread_mutex_t lock;
    pthread_cond_t changed;   /* a chunk finished (the writer waits) or one was written (workers wait) */
    int next;                 /* next chunk to claim */
    int written;              /* chunks written so far */
    bool failed;
    chunk_slot *slots;        /* `window` slots; chunk i uses slots[i % window] */
} encoder;

/* Chunk i: initialize and feed under the lock, then pack and compress (the expensive part) outside it. */
static exr_result_t encode_one(encoder *e, int i, exr_encode_pipeline_t *enc)
{
    int y = e->y0 + i * e->lpc;
    exr_chunk_info_t cinfo;
    memset(&cinfo, 0, sizeof cinfo);
    memset(enc, 0, sizeof *enc);
    pthread_mutex_lock(&e->lock);
    exr_result_t rc = exr_write_scanline_chunk_info(e->ctxt, e->part, y, &cinfo);
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_initialize(e->ctxt, e->part, &cinfo, enc);
    if (rc == EXR_ERR_SUCCESS) rc = e->feed(e->user, enc, cinfo.start_y, cinfo.height);
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_choose_default_routines(e->ctxt, e->part, enc);
    pthread_mutex_unlock(&e->lock);
    io_exr_compress_wrap wrap = {NULL};
    if (rc == EXR_ERR_SUCCESS && enc->compress_fn) {
        wrap.orig = enc->compress_fn;
        enc->encoding_user_data = &wrap;
        enc->compress_fn = io_exr_compress_no_expand;
    }
    /* No yield or write here: the writer writes the chunks in order. */
    enc->yield_until_ready_fn = NULL;
    enc->write_fn = NULL;
    if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_run(e->ctxt, e->part, enc);
    enc->encoding_user_data = NULL;
    return rc;
}

static exr_result_t write_one(encoder *e, int i, exr_encode_pipeline_t *enc)
{
    return exr_write_scanline_chunk(e->ctxt, e->part, e->y0 + i * e->lpc, enc->compressed_buffer,
                                    enc->compressed_bytes);
}

static void *worker(void *arg)
{
    encoder *e = arg;
    pthread_mutex_lock(&e->lock);
    for (;;) {
        /* Claim the next chunk once its slot is free (the chunk `window` before it is written). */
        while (!e->failed && e->next < e->count && e->next >= e->written + e->window)
            pthread_cond_wait(&e->changed, &e->lock);
        if (e->failed || e->next >= e->count) break;
        int i = e->next++;
        pthread_mutex_unlock(&e->lock);
        /* Encoded in place: the pipeline points into itself (its small channel store), so it is never copied. */
        chunk_slot *s = &e->slots[i % e->window];
        exr_result_t rc = encode_one(e, i, &s->enc);
        pthread_mutex_lock(&e->lock);
        s->rc = rc, s->done = true;
        pthread_cond_broadcast(&e->changed);
    }
    pthread_mutex_unlock(&e->lock);
    return NULL;
}

exr_result_t io_exr_encode_chunks(exr_context_t ctxt, int part, int y0, int count, int lines_per_chunk,
                                  io_exr_feed_fn feed, void *user, int threads)
{
    encoder e = {.ctxt = ctxt, .part = part, .y0 = y0, .count = count, .lpc = lines_per_chunk, .feed = feed,
                 .user = user};
    if (threads > count) threads = count;
    if (threads <= 1) {
        /* One thread: encode and write each chunk in turn (no worker, no lock needed). */
        pthread_mutex_init(&e.lock, NULL);
        exr_result_t rc = EXR_ERR_SUCCESS;
        for (int i = 0; i < count && rc == EXR_ERR_SUCCESS; ++i) {
            exr_encode_pipeline_t enc;
            rc = encode_one(&e, i, &enc);
            if (rc == EXR_ERR_SUCCESS) rc = write_one(&e, i, &enc);
            exr_encoding_destroy(ctxt, &enc);
        }
        pthread_mutex_destroy(&e.lock);
        return rc;
    }
    /* Two finished chunks per worker may wait for the writer: enough to keep every worker busy while one chunk is
     * written, few enough that a wide band's chunks are never all in memory at once. */
    e.window = 2 * threads;
    e.slots = calloc((size_t)e.window, sizeof *e.slots);
    pthread_t *tids = calloc((size_t)threads, sizeof *tids);
    if (!e.slots || !tids) {
        free(e.slots);
        free(tids);
        return EXR_ERR_OUT_OF_MEMORY;
    }
    pthread_mutex_init(&e.lock, NULL);
    pthread_cond_init(&e.changed, NULL);
    int started = 0;
    for (; started < threads; ++started)
        if (pthread_create(&tids[started], NULL, worker, &e) != 0) break;
    exr_result_t rc = started > 0 ? EXR_ERR_SUCCESS : EXR_ERR_OUT_OF_MEMORY;
    /* The writer: chunk i as soon as it is compressed, in order. */
    pthread_mutex_lock(&e.lock);
    for (int i = 0; i < count && rc == EXR_ERR_SUCCESS; ++i) {
        chunk_slot *s = &e.slots[i % e.window];
        while (!s->done) pthread_cond_wait(&e.changed, &e.lock);
        rc = s->rc;
        if (rc == EXR_ERR_SUCCESS) rc = write_one(&e, i, &s->enc);
        exr_encoding_destroy(ctxt, &s->enc);
        s->done = false;
        e.written = i + 1;
        pthread_cond_broadcast(&e.changed);
    }
    if (rc != EXR_ERR_SUCCESS) e.failed = true;
    pthread_cond_broadcast(&e.changed);
    pthread_mutex_unlock(&e.lock);
    for (int t = 0; t < started; ++t) pthread_join(tids[t], NULL);
    /* After a failure, chunks compressed but never written. */
    for (int k = 0; k < e.window; ++k)
        if (e.slots[k].done) exr_encoding_destroy(ctxt, &e.slots[k].enc);
    pthread_cond_destroy(&e.changed);
    pthread_mutex_destroy(&e.lock);
    free(e.slots);
    free(tids);
    return rc;
}
