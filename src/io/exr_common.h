/* vksky image I/O: what the OpenEXR writer and reader share. Internal to src/io/. */
#ifndef VKSKY_IO_EXR_COMMON_H
#define VKSKY_IO_EXR_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include <openexr.h>

/* Longest layer name accepted (channel names are "<layer>.R" etc.). */
#define IO_EXR_MAX_LAYER_NAME 200

/* The OpenEXRCore error callback delivers messages on the failing thread; keep the last one per thread instead of
   letting the library print to stderr. Install io_exr_error_handler in the context initializer, clear the message
   before a call sequence, and read it back with io_exr_msg (the library's default text when none was captured). */
void io_exr_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg);
void io_exr_clear_msg(void);
const char *io_exr_msg(exr_result_t rc);

/* Channel name for layer `layer` ("" = the default layer) and component index c (0..3 = R,G,B,A). */
void io_exr_channel_name(char *out, size_t out_size, const char *layer, int c);

/* One layer for the shared encode loop (exr_layers.c): `channels` (3 or 4) interleaved values per pixel, top row
   first, from exactly one of `half` (stored bits) or `f32` (converted with io_float_to_half a chunk at a time). */
typedef struct io_exr_write_layer {
    const char *name;
    int channels;
    const uint16_t *half;
    const float *f32;
    int store_float;      /* with f32: stored as FLOAT channels (else converted to HALF) */
} io_exr_write_layer;

/* Writes the layers as one scanline part of HALF channels, ZIP, atomically (atomic_file.h), with the header
   attributes of `meta` (exr_meta.h; NULL: none). The caller has validated everything (size, names unique and short
   enough, channel counts, pixels present). 0, or -1 + err ("cannot write 'PATH': ..."). Used by io_write_exr(_meta)
   and io_write_exr_layers. */
struct io_exr_meta;
int io_exr_write_layers_half(const char *path, int width, int height, const io_exr_write_layer *layers,
                             int layer_count, const struct io_exr_meta *meta, char *err, size_t err_size);

/* The attributes of an io_exr_meta (exr_meta.h) onto a part being written, before its header is written. */
exr_result_t io_exr_set_meta(exr_context_t ctxt, int part, const struct io_exr_meta *meta);

/* Writers' output: OpenEXRCore writes through these callbacks into an fd the writer owns (pwrite at the library's
   offsets; errno of the first failure kept for the message). */
typedef struct io_exr_out_stream {
    int fd;
    int err_no; /* errno of the first failed write, 0 if none */
} io_exr_out_stream;
int64_t io_exr_fd_write(exr_const_context_t ctxt, void *userdata, const void *buffer, uint64_t sz, uint64_t offset,
                        exr_stream_error_func_ptr_t error_cb);
void io_exr_fd_destroy(exr_const_context_t ctxt, void *userdata, int failed);
/* A writer's context initializer: io_exr_error_handler's messages, the callbacks above writing into out's fd. */
exr_context_initializer_t io_exr_fd_initializer(io_exr_out_stream *out);

/* The zlib level of the process's settings (encode_settings.h) onto a part being written (nothing if default). */
exr_result_t io_exr_apply_compression_level(exr_context_t ctxt, int part);

/* The library's compressor wrapped so that a chunk is stored raw unless compression makes it strictly smaller
   (exr_common.c says why): set enc->encoding_user_data to a wrap holding the original compress_fn. */
typedef struct io_exr_compress_wrap {
    exr_result_t (*orig)(exr_encode_pipeline_t *);
} io_exr_compress_wrap;
exr_result_t io_exr_compress_no_expand(exr_encode_pipeline_t *enc);

#endif /* VKSKY_IO_EXR_COMMON_H */
