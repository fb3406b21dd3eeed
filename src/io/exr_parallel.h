/* vksky image I/O: EXR chunks compressed on worker threads and written in order (issue 27). Internal to src/io/ (the
 * writers exr_layers.c, exr_stream.c and exr_layers_stream.c call it); the settings are process-wide, set once by
 * the app (io/encode_settings.h). ZIP and ZIPS chunks are compressed by libdeflate (exr_deflate.h), the others by
 * OpenEXRCore. */
#ifndef VKSKY_IO_EXR_PARALLEL_H
#define VKSKY_IO_EXR_PARALLEL_H
#include <openexr.h>

/* Points the encoder's channels at the rows of the chunk starting at row y (`rows` rows): sets encode_from_ptr,
 * strides and the user data type of each of enc->channels. Called under the encoder's lock, one chunk at a time;
 * the data it points at must stay unchanged until the call that handed the chunk over returns. EXR_ERR_SUCCESS, or
 * an error that fails the encode. */
typedef exr_result_t (*io_exr_feed_fn)(void *user, exr_encode_pipeline_t *enc, int y, int rows);

/* A chunk pool: worker threads that live as long as the file, so that a band's chunks start compressing while the
 * previous band's last ones still compress (a streamed writer hands its bands over one by one). Chunks are written in
 * the order they were handed over, by whichever worker finishes the next one; at most 2 x threads finished chunks
 * wait, so memory stays bounded. The bytes are the same for every thread count: each chunk is compressed alone and
 * the order is fixed. With threads <= 1 there is no worker: io_exr_pool_chunks encodes and writes in the caller. */
typedef struct io_exr_pool io_exr_pool;

/* For part `part` of a context whose header is written. NULL when out of memory. */
io_exr_pool *io_exr_pool_create(exr_context_t ctxt, int part, int lines_per_chunk, int threads);
/* Hands over the `count` chunks starting at row y0 (y0 + lines_per_chunk, ...) and returns once `feed` has pointed
 * each of them at its rows and the library has packed them (copied them out): the rows may then change. The chunks
 * may still be compressing and be written later. The first failure of any chunk so far, else EXR_ERR_SUCCESS. */
exr_result_t io_exr_pool_chunks(io_exr_pool *p, int y0, int count, io_exr_feed_fn feed, void *user);
/* Waits until every chunk handed over is written. The first failure, else EXR_ERR_SUCCESS. */
exr_result_t io_exr_pool_drain(io_exr_pool *p);
/* Stops the workers (chunks not yet written are dropped: call drain first for a whole file) and frees the pool; before
 * exr_finish. NULL is accepted. */
void io_exr_pool_destroy(io_exr_pool *p);

/* The whole of a part at once: a pool for these chunks, drained and destroyed. */
exr_result_t io_exr_encode_chunks(exr_context_t ctxt, int part, int y0, int count, int lines_per_chunk,
                                  io_exr_feed_fn feed, void *user, int threads);
#endif
