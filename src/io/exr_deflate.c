/* vksky image I/O: ZIP / ZIPS chunks through libdeflate (exr_deflate.h). */
#include "io/exr_deflate.h"
#include "io/encode_settings.h"

#include <libdeflate.h>
#include <stdint.h>
#include <string.h>

struct libdeflate_compressor *io_exr_deflate_alloc(int exr_zip_level)
{
    /* -1 (unset): our default, OpenEXR 3.2's (EXR_DEFAULT_ZLIB_COMPRESS_LEVEL, 4); 3.1 used zlib's 6. */
    int level = exr_zip_level < 0 ? IO_EXR_DEFAULT_ZIP_LEVEL : exr_zip_level > 12 ? 12 : exr_zip_level;
    return libdeflate_alloc_compressor(level);
}

void io_exr_deflate_free(struct libdeflate_compressor *c)
{
    if (c) libdeflate_free_compressor(c);
}

void io_exr_zip_predict(unsigned char *out, const unsigned char *raw, size_t n)
{
    if (n == 0) return;
    /* Even bytes first, then odd ones (the first half gets the extra byte of an odd count). */
    size_t pairs = n / 2, half = (n + 1) / 2;
    unsigned char *t1 = out, *t2 = out + half;
    for (size_t i = 0; i < pairs; ++i) {
        t1[i] = raw[2 * i];
        t2[i] = raw[2 * i + 1];
    }
    if (n & 1) t1[pairs] = raw[n - 1];
    /* Each byte's difference from the one before, + 128 (mod 256); backwards, so the one before is still original. */
    for (size_t i = n - 1; i > 0; --i) out[i] = (unsigned char)(out[i] - out[i - 1] + 128u);
}

/* A pipeline buffer of at least `want` bytes, through the pipeline's own allocator. */
static exr_result_t ensure(exr_encode_pipeline_t *enc, exr_transcoding_pipeline_buffer_id_t id, void **buf,
                           size_t *cap, size_t want)
{
    if (*buf && *cap >= want) return EXR_ERR_SUCCESS;
    if (!enc->alloc_fn || !enc->free_fn) return EXR_ERR_INVALID_ARGUMENT;
    if (*buf && *cap > 0) enc->free_fn(id, *buf);
    *buf = enc->alloc_fn(id, want);
    *cap = *buf ? want : 0;
    return *buf ? EXR_ERR_SUCCESS : EXR_ERR_OUT_OF_MEMORY;
}

exr_result_t io_exr_deflate_chunk(exr_encode_pipeline_t *enc, struct libdeflate_compressor *c)
{
    size_t n = (size_t)enc->packed_bytes;
    if (!c || !enc->packed_buffer || n == 0) return EXR_ERR_INVALID_ARGUMENT;
    exr_result_t rc = ensure(enc, EXR_TRANSCODE_BUFFER_SCRATCH1, &enc->scratch_buffer_1, &enc->scratch_alloc_size_1, n);
    if (rc == EXR_ERR_SUCCESS)
        rc = ensure(enc, EXR_TRANSCODE_BUFFER_COMPRESSED, &enc->compressed_buffer, &enc->compressed_alloc_size, n);
    if (rc != EXR_ERR_SUCCESS) return rc;
    io_exr_zip_predict(enc->scratch_buffer_1, enc->packed_buffer, n);
    /* Room for one byte less than the raw chunk: libdeflate returns 0 when the stream would not fit, and a chunk is
     * stored compressed only if strictly smaller (a reader takes packed size == unpacked size for "stored raw"). */
    size_t out = n > 1 ? libdeflate_zlib_compress(c, enc->scratch_buffer_1, n, enc->compressed_buffer, n - 1) : 0;
    if (out == 0) {
        memcpy(enc->compressed_buffer, enc->packed_buffer, n);
        out = n;
    }
    enc->compressed_bytes = out;
    return EXR_ERR_SUCCESS;
}

void io_exr_zip_unpredict(unsigned char *out, unsigned char *pred, size_t n)
{
    if (n == 0) return;
    /* Undo the differences in place (forwards: the byte before is already restored), then re-interleave. */
    for (size_t i = 1; i < n; ++i) pred[i] = (unsigned char)(pred[i - 1] + pred[i] - 128u);
    size_t pairs = n / 2, half = (n + 1) / 2;
    const unsigned char *t1 = pred, *t2 = pred + half;
    for (size_t i = 0; i < pairs; ++i) {
        out[2 * i] = t1[i];
        out[2 * i + 1] = t2[i];
    }
    if (n & 1) out[n - 1] = t1[pairs];
}

exr_result_t io_exr_inflate_chunk(exr_decode_pipeline_t *dec, struct libdeflate_decompressor *d, unsigned char *scratch,
                                  size_t scratch_size)
{
    size_t packed = (size_t)dec->chunk.packed_size, unpacked = (size_t)dec->chunk.unpacked_size;
    if (packed == 0) return EXR_ERR_SUCCESS;
    if (!dec->packed_buffer || !dec->unpacked_buffer) return EXR_ERR_INVALID_ARGUMENT;
    if (packed == unpacked) { /* stored raw: the writer's chunk did not get smaller */
        if (dec->unpacked_buffer != dec->packed_buffer) memcpy(dec->unpacked_buffer, dec->packed_buffer, unpacked);
        return EXR_ERR_SUCCESS;
    }
    if (!d || !scratch || scratch_size < unpacked) return EXR_ERR_INVALID_ARGUMENT;
    size_t got = 0;
    enum libdeflate_result r = libdeflate_zlib_decompress(d, dec->packed_buffer, packed, scratch, unpacked, &got);
    if (r != LIBDEFLATE_SUCCESS || got != unpacked) return EXR_ERR_CORRUPT_CHUNK;
    io_exr_zip_unpredict(dec->unpacked_buffer, scratch, unpacked);
    return EXR_ERR_SUCCESS;
}
