/* vksky image I/O: ZIP and ZIPS chunks compressed by libdeflate instead of zlib (issue 27). Internal to src/io/
 * (exr_parallel.c installs it as the chunks' compress step).
 *
 * A ZIP chunk is the OpenEXR file format's: the packed bytes split into even and odd bytes (the two halves one after
 * the other), each byte replaced by its difference from the one before plus 128, and the result as one zlib stream;
 * a chunk that does not get strictly smaller is stored raw. Any zlib stream is valid there, so a libdeflate stream is
 * read by every OpenEXR (3.1 inflates it with zlib) and by OpenImageIO and Blender. OpenEXR itself moved from zlib to
 * libdeflate in 3.2 (its default level there: 4); Debian 12's 3.1 still calls zlib's compress2 at level 6. */
#ifndef VKSKY_IO_EXR_DEFLATE_H
#define VKSKY_IO_EXR_DEFLATE_H
#include <openexr.h>

struct libdeflate_compressor;
struct libdeflate_decompressor;

/* The compressor for an OpenEXR part's zip level (exr_get_zip_compression_level: -1, unset: IO_EXR_DEFAULT_ZIP_LEVEL,
 * 4, OpenEXR 3.2's default; 3.1 writes zlib 6). One per thread: a compressor is not shareable. NULL when out of memory. */
struct libdeflate_compressor *io_exr_deflate_alloc(int exr_zip_level);
void io_exr_deflate_free(struct libdeflate_compressor *c);

/* The compress step of a ZIP or ZIPS chunk: enc->packed_buffer (packed_bytes) into enc->compressed_buffer
 * (compressed_bytes), the scratch in scratch_buffer_1; both buffers grown through enc->alloc_fn / enc->free_fn, which
 * the caller must set (exr_encoding_destroy frees them the same way). */
exr_result_t io_exr_deflate_chunk(exr_encode_pipeline_t *enc, struct libdeflate_compressor *c);

/* The file format's predictor alone: `n` packed bytes into `out` (n bytes), as the compress step does (tests). */
void io_exr_zip_predict(unsigned char *out, const unsigned char *raw, size_t n);

/* Reading (issue 28): the decompress step of a ZIP or ZIPS chunk, dec->packed_buffer into dec->unpacked_buffer (both
 * set up by the pipeline before its decompress step), inflated by libdeflate into `scratch` (at least the chunk's
 * unpacked size; the caller's) and un-predicted. A stored-raw chunk (packed size == unpacked size) is copied, as
 * OpenEXRCore does. EXR_ERR_CORRUPT_CHUNK when the stream is bad or inflates to another size. */
exr_result_t io_exr_inflate_chunk(exr_decode_pipeline_t *dec, struct libdeflate_decompressor *d, unsigned char *scratch,
                                  size_t scratch_size);
/* The predictor undone: `pred` (n bytes, overwritten) into `out` (n bytes); the inverse of io_exr_zip_predict. */
void io_exr_zip_unpredict(unsigned char *out, unsigned char *pred, size_t n);
#endif
