/* vksky image I/O: what the OpenEXR writer and reader share: the library's error messages, captured per thread,
   and the channel names of a layer. See exr_common.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/encode_settings.h"
#include "io/exr_common.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

/* The OpenEXRCore error callback delivers messages on the failing thread; keep the last one per thread
   instead of letting the library print to stderr. */
static _Thread_local char g_exr_msg[512];

void io_exr_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(g_exr_msg, sizeof g_exr_msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

const char *io_exr_msg(exr_result_t rc)
{
    if (g_exr_msg[0]) return g_exr_msg;
    return exr_get_default_error_message(rc);
}

void io_exr_clear_msg(void) { g_exr_msg[0] = '\0'; }

/* Channel name for layer `name` and component index c (0..3 = R,G,B,A). */
void io_exr_channel_name(char *out, size_t out_size, const char *layer, int c)
{
    static const char comp[4] = {'R', 'G', 'B', 'A'};
    if (layer[0])
        snprintf(out, out_size, "%s.%c", layer, comp[c]);
    else
        snprintf(out, out_size, "%c", comp[c]);
}

int64_t io_exr_fd_write(exr_const_context_t ctxt, void *userdata, const void *buffer, uint64_t sz,
                                uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    io_exr_out_stream *s = (io_exr_out_stream *)userdata;
    const uint8_t *p = (const uint8_t *)buffer;
    uint64_t done = 0;
    while (done < sz) {
        uint64_t want = sz - done;
        if (want > (uint64_t)1 << 30) want = (uint64_t)1 << 30;
        ssize_t n = pwrite(s->fd, p + done, (size_t)want, (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            int e = (n < 0) ? errno : EIO;
            if (!s->err_no) s->err_no = e;
            if (error_cb) error_cb(ctxt, EXR_ERR_WRITE_IO, "write failed: %s", strerror(e));
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)sz;
}

void io_exr_fd_destroy(exr_const_context_t ctxt, void *userdata, int failed)
{
    (void)ctxt;
    (void)userdata;
    (void)failed; /* the fd is owned and closed by the writer */
}

exr_context_initializer_t io_exr_fd_initializer(io_exr_out_stream *out)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = io_exr_error_handler;
    init.user_data = out;
    init.write_fn = io_exr_fd_write;
    init.destroy_fn = io_exr_fd_destroy;
    return init;
}

/* OpenEXRCore 3.1.x keeps a ZIP-compressed chunk whose compressed size is exactly equal to the raw size, but
   every reader (Core and the C++ library) treats packed_size == unpacked_size as "stored uncompressed", so such a
   chunk would read back as garbage (reproducible with small 4-channel chunks). Wrap the library's compressor and
   store the raw packed data whenever compression does not make the chunk strictly smaller. */
exr_result_t io_exr_compress_no_expand(exr_encode_pipeline_t *enc)
{
    const io_exr_compress_wrap *wrap = (const io_exr_compress_wrap *)enc->encoding_user_data;
    if (!wrap || !wrap->orig) return EXR_ERR_INVALID_ARGUMENT;
    exr_result_t rc = wrap->orig(enc);
    if (rc != EXR_ERR_SUCCESS) return rc;
    if (enc->compressed_bytes >= enc->packed_bytes && enc->compressed_buffer != enc->packed_buffer) {
        if (!enc->compressed_buffer || !enc->packed_buffer || enc->compressed_alloc_size < enc->packed_bytes)
            return EXR_ERR_CORRUPT_CHUNK;
        memcpy(enc->compressed_buffer, enc->packed_buffer, (size_t)enc->packed_bytes);
        enc->compressed_bytes = (size_t)enc->packed_bytes;
    }
    return EXR_ERR_SUCCESS;
}

exr_result_t io_exr_apply_compression_level(exr_context_t ctxt, int part)
{
    /* Always set, so that no path falls back to the library's own default (OpenEXR 3.1's zlib 6). */
    int level = io_encode_settings_get().zip_level;
    return exr_set_zip_compression_level(ctxt, part, level > 0 ? level : IO_EXR_DEFAULT_ZIP_LEVEL);
}
