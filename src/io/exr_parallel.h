/* vksky image I/O: EXR chunks compressed on worker threads, written in order by one writer (issue 27). Internal to
 * src/io/ (the writers exr_layers.c and exr_stream.c call it); the settings are process-wide, set once by the app
 * (io/encode_settings.h). */
#ifndef VKSKY_IO_EXR_PARALLEL_H
#define VKSKY_IO_EXR_PARALLEL_H
#include <openexr.h>

/* Points the encoder's channels at the rows of the chunk starting at row y (`rows` rows): sets encode_from_ptr,
 * strides and the user data type of each of enc->channels. Called under the encoder's lock, one chunk at a time;
 * the data it points at must stay unchanged until io_exr_encode_chunks returns. EXR_ERR_SUCCESS, or an error that
 * fails the encode. */
typedef exr_result_t (*io_exr_feed_fn)(void *user, exr_encode_pipeline_t *enc, int y, int rows);

/* Encodes the `count` chunks of part `part` that start at rows y0, y0 + lines_per_chunk, ... and writes them to the
 * file in that order. With threads > 1, workers claim chunks in order and compress them concurrently (at most a
 * small window of finished chunks waits for the writer, so memory stays bounded); the calling thread writes. The
 * bytes are the same for every thread count: each chunk is compressed alone, and the writer's order is fixed. */
exr_result_t io_exr_encode_chunks(exr_context_t ctxt, int part, int y0, int count, int lines_per_chunk,
                                  io_exr_feed_fn feed, void *user, int threads);
#endif
