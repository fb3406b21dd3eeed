/* vksky image I/O: OpenEXR via the OpenEXRCore C API (3.1), PNG via libpng. See image_io.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/image_io.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <openexr.h>
#include <png.h>

/* Largest image we accept in either direction (also keeps every size computation far from overflow). */
#define IO_MAX_DIM (1 << 16)

/* ------------------------------------------------------------------------------------------------ */
/* Error messages                                                                                   */
/* ------------------------------------------------------------------------------------------------ */

static void set_err(char *err, size_t err_size, const char *fmt, ...)
{
    if (!err || err_size == 0) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
    if (n < 0) {
        err[0] = '\0';
        return;
    }
    /* One line, no trailing newline. */
    for (char *p = err; *p; ++p) {
        if (*p == '\n' || *p == '\r') *p = ' ';
    }
    size_t len = strlen(err);
    while (len > 0 && err[len - 1] == ' ') err[--len] = '\0';
}

static const char *safe_path(const char *path) { return path ? path : "(null)"; }

/* ------------------------------------------------------------------------------------------------ */
/* Path helpers                                                                                     */
/* ------------------------------------------------------------------------------------------------ */

/* Splits `path` into a directory (for stat/access: "." when there is no slash) and the length of the
   directory prefix including its trailing slash (0 when there is none). Returns -1 when the basename is
   empty or the path is too long. */
static int split_path(const char *path, char *dir, size_t dir_size, size_t *prefix_len)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        if (dir_size < 2) return -1;
        strcpy(dir, ".");
        *prefix_len = 0;
        return path[0] ? 0 : -1;
    }
    if (slash[1] == '\0') return -1; /* ends with '/': no basename */
    size_t plen = (size_t)(slash - path) + 1;
    size_t dlen = (slash == path) ? 1 : plen - 1; /* "/x" -> dir "/" */
    if (dlen + 1 > dir_size) return -1;
    memcpy(dir, path, dlen);
    dir[dlen] = '\0';
    *prefix_len = plen;
    return 0;
}

/* "<dir>/.<basename>.tmp.<pid>" */
static int make_temp_path(const char *path, char *out, size_t out_size)
{
    char dir[PATH_MAX];
    size_t prefix_len = 0;
    if (split_path(path, dir, sizeof dir, &prefix_len) != 0) return -1;
    int n = snprintf(out, out_size, "%.*s.%s.tmp.%ld", (int)prefix_len, path, path + prefix_len, (long)getpid());
    return (n < 0 || (size_t)n >= out_size) ? -1 : 0;
}

int io_check_writable(const char *path, char *err, size_t err_size)
{
    if (!path || !path[0]) {
        set_err(err, err_size, "cannot write '%s': empty path", safe_path(path));
        return -1;
    }
    char dir[PATH_MAX];
    size_t prefix_len = 0;
    if (strlen(path) >= PATH_MAX - 32) {
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(ENAMETOOLONG));
        return -1;
    }
    if (split_path(path, dir, sizeof dir, &prefix_len) != 0) {
        set_err(err, err_size, "cannot write '%s': path names a directory, not a file", path);
        return -1;
    }
    struct stat st;
    if (stat(dir, &st) != 0) {
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(ENOTDIR));
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(EISDIR));
        return -1;
    }
    /* access() says yes to root almost everywhere: probe by creating (and removing) the temp file the writers
       would use. An existing temp file is fine: the writers truncate it. */
    char tmp[PATH_MAX + 64];
    if (make_temp_path(path, tmp, sizeof tmp) != 0) {
        set_err(err, err_size, "cannot write '%s': invalid or too long path", path);
        return -1;
    }
    int fd;
    do {
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        if (errno == EEXIST) return 0;
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    close(fd);
    unlink(tmp);
    return 0;
}

/* Opens the temp file for `path`; on failure sets err and returns -1. */
static int open_temp(const char *path, char *tmp, size_t tmp_size, char *err, size_t err_size)
{
    if (!path || !path[0]) {
        set_err(err, err_size, "cannot write '%s': empty path", safe_path(path));
        return -1;
    }
    if (make_temp_path(path, tmp, tmp_size) != 0) {
        set_err(err, err_size, "cannot write '%s': invalid or too long path", path);
        return -1;
    }
    int fd;
    do {
        fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    } while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        set_err(err, err_size, "cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    return fd;
}

/* fsync + close `fd` (if >= 0) and rename tmp -> path. On failure unlinks tmp, sets err and returns -1.
   `fd` is always closed. */
static int commit_temp(int fd, const char *tmp, const char *path, char *err, size_t err_size)
{
    if (fd >= 0) {
        if (fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
            int e = errno;
            close(fd);
            unlink(tmp);
            set_err(err, err_size, "cannot write '%s': %s", path, strerror(e));
            return -1;
        }
        if (close(fd) != 0) {
            int e = errno;
            unlink(tmp);
            set_err(err, err_size, "cannot write '%s': %s", path, strerror(e));
            return -1;
        }
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        set_err(err, err_size, "cannot write '%s': rename from temp file failed: %s", path, strerror(e));
        return -1;
    }
    return 0;
}

static void abort_temp(int fd, const char *tmp)
{
    if (fd >= 0) close(fd);
    unlink(tmp);
}

/* ------------------------------------------------------------------------------------------------ */
/* Half floats                                                                                      */
/* ------------------------------------------------------------------------------------------------ */

uint16_t io_float_to_half(float f)
{
    uint32_t x;
    memcpy(&x, &f, sizeof x);
    uint16_t sign = (uint16_t)((x >> 16) & 0x8000u);
    uint32_t ax = x & 0x7fffffffu;

    if (ax >= 0x7f800000u) {
        if (ax == 0x7f800000u) return (uint16_t)(sign | 0x7c00u); /* infinity */
        return (uint16_t)(sign | 0x7e00u | ((ax >> 13) & 0x3ffu)); /* NaN: quiet, keep top payload bits */
    }
    if (ax > 0x477fe000u) return (uint16_t)(sign | 0x7bffu); /* > 65504: clamp to max finite */

    uint32_t e = ax >> 23;
    if (e < 113) {
        /* Result is a half denormal (or zero, or rounds up to the smallest normal). */
        if (e < 102) return sign; /* < 2^-25: rounds to zero */
        uint32_t m = (ax & 0x7fffffu) | 0x800000u;
        uint32_t shift = 126u - e; /* 14..24 */
        uint32_t h = m >> shift;
        uint32_t rem = m & ((1u << shift) - 1u);
        uint32_t halfway = 1u << (shift - 1u);
        if (rem > halfway || (rem == halfway && (h & 1u))) ++h;
        return (uint16_t)(sign | h);
    }
    /* Normal: rebias exponent (127 -> 15), round mantissa 23 -> 10 bits; carries ripple into the exponent. */
    uint32_t h = ((e - 112u) << 10) | ((ax >> 13) & 0x3ffu);
    uint32_t rem = ax & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) ++h;
    return (uint16_t)(sign | h);
}

float io_half_to_float(uint16_t hv)
{
    uint32_t sign = (uint32_t)(hv & 0x8000u) << 16;
    uint32_t e = (hv >> 10) & 0x1fu;
    uint32_t m = hv & 0x3ffu;
    uint32_t x;
    if (e == 0x1fu) {
        x = sign | 0x7f800000u | (m << 13); /* inf / NaN (payload kept) */
    } else if (e != 0) {
        x = sign | ((e + 112u) << 23) | (m << 13);
    } else if (m == 0) {
        x = sign;
    } else {
        /* Denormal: normalise. */
        uint32_t ee = 113;
        while (!(m & 0x400u)) {
            m <<= 1;
            --ee;
        }
        x = sign | (ee << 23) | ((m & 0x3ffu) << 13);
    }
    float f;
    memcpy(&f, &x, sizeof f);
    return f;
}

/* ------------------------------------------------------------------------------------------------ */
/* OpenEXR                                                                                          */
/* ------------------------------------------------------------------------------------------------ */

/* The OpenEXRCore error callback delivers messages on the failing thread; keep the last one per thread
   instead of letting the library print to stderr. */
static _Thread_local char g_exr_msg[512];

static void exr_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(g_exr_msg, sizeof g_exr_msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

static const char *exr_msg(exr_result_t rc)
{
    if (g_exr_msg[0]) return g_exr_msg;
    return exr_get_default_error_message(rc);
}

typedef struct exr_out_stream {
    int fd;
    int err_no; /* errno of the first failed write, 0 if none */
} exr_out_stream;

static int64_t exr_stream_write(exr_const_context_t ctxt, void *userdata, const void *buffer, uint64_t sz,
                                uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_out_stream *s = (exr_out_stream *)userdata;
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

static void exr_stream_destroy(exr_const_context_t ctxt, void *userdata, int failed)
{
    (void)ctxt;
    (void)userdata;
    (void)failed; /* the fd is owned and closed by io_write_exr */
}

/* OpenEXRCore 3.1.x keeps a ZIP-compressed chunk whose compressed size is exactly equal to the raw size, but
   every reader (Core and the C++ library) treats packed_size == unpacked_size as "stored uncompressed", so such a
   chunk would read back as garbage (reproducible with small 4-channel chunks). Wrap the library's compressor and
   store the raw packed data whenever compression does not make the chunk strictly smaller. */
typedef struct exr_compress_wrap {
    exr_result_t (*orig)(exr_encode_pipeline_t *);
} exr_compress_wrap;

static exr_result_t exr_compress_no_expand(exr_encode_pipeline_t *enc)
{
    const exr_compress_wrap *wrap = (const exr_compress_wrap *)enc->encoding_user_data;
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

/* Channel name for layer `name` and component index c (0..3 = R,G,B,A). */
static void exr_channel_name(char *out, size_t out_size, const char *layer, int c)
{
    static const char comp[4] = {'R', 'G', 'B', 'A'};
    if (layer[0])
        snprintf(out, out_size, "%s.%c", layer, comp[c]);
    else
        snprintf(out, out_size, "%c", comp[c]);
}

#define EXR_MAX_LAYER_NAME 200

int io_write_exr(const char *path, int width, int height, const io_exr_layer *layers, int layer_count, char *err,
                 size_t err_size)
{
    const char *p = safe_path(path);
    if (!path || !path[0]) {
        set_err(err, err_size, "cannot write '%s': empty path", p);
        return -1;
    }
    if (width <= 0 || height <= 0 || width > IO_MAX_DIM || height > IO_MAX_DIM) {
        set_err(err, err_size, "cannot write '%s': invalid image size %dx%d", p, width, height);
        return -1;
    }
    if (!layers || layer_count <= 0 || layer_count > 1000) {
        set_err(err, err_size, "cannot write '%s': invalid layer list (%d layers)", p, layer_count);
        return -1;
    }
    for (int i = 0; i < layer_count; ++i) {
        if (!layers[i].name || !layers[i].rgba_half) {
            set_err(err, err_size, "cannot write '%s': layer %d has no %s", p, i, layers[i].name ? "pixels" : "name");
            return -1;
        }
        if (strlen(layers[i].name) > EXR_MAX_LAYER_NAME) {
            set_err(err, err_size, "cannot write '%s': layer %d name too long", p, i);
            return -1;
        }
        for (int j = 0; j < i; ++j) {
            if (strcmp(layers[i].name, layers[j].name) == 0) {
                set_err(err, err_size, "cannot write '%s': duplicate layer name '%s'", p, layers[i].name);
                return -1;
            }
        }
    }

    char tmp[PATH_MAX + 64];
    int fd = open_temp(path, tmp, sizeof tmp, err, err_size);
    if (fd < 0) return -1;

    exr_out_stream stream = {fd, 0};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_handler;
    init.user_data = &stream;
    init.write_fn = exr_stream_write;
    init.destroy_fn = exr_stream_destroy;

    exr_context_t ctxt = NULL;
    exr_result_t rc;
    const char *stage = "start";
    g_exr_msg[0] = '\0';

    rc = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    /* Names longer than 31 bytes need the "long names" file flag (only set when needed: old readers reject it). */
    int long_names = 0;
    for (int l = 0; l < layer_count; ++l) long_names |= strlen(layers[l].name) + 2 > 31;
    if (long_names) {
        stage = "enable long names";
        rc = exr_set_longname_support(ctxt, 1);
        if (rc != EXR_ERR_SUCCESS) goto fail;
    }

    int part = 0;
    stage = "add part";
    rc = exr_add_part(ctxt, "", EXR_STORAGE_SCANLINE, &part);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    stage = "header";
    rc = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_ZIP);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    stage = "add channel";
    for (int l = 0; l < layer_count; ++l) {
        for (int c = 0; c < 4; ++c) {
            char name[EXR_MAX_LAYER_NAME + 8];
            exr_channel_name(name, sizeof name, layers[l].name, c);
            rc = exr_add_channel(ctxt, part, name, EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
            if (rc != EXR_ERR_SUCCESS) goto fail;
        }
    }

    stage = "write header";
    rc = exr_write_header(ctxt);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    int32_t lines_per_chunk = 0;
    stage = "chunk layout";
    rc = exr_get_scanlines_per_chunk(ctxt, part, &lines_per_chunk);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    if (lines_per_chunk <= 0) {
        rc = EXR_ERR_INVALID_ATTR;
        goto fail;
    }

    for (int y = 0; y < height; y += lines_per_chunk) {
        exr_chunk_info_t cinfo;
        exr_encode_pipeline_t enc;
        memset(&cinfo, 0, sizeof cinfo);
        memset(&enc, 0, sizeof enc);
        stage = "chunk info";
        rc = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rc != EXR_ERR_SUCCESS) goto fail;
        stage = "encode init";
        rc = exr_encoding_initialize(ctxt, part, &cinfo, &enc);
        if (rc != EXR_ERR_SUCCESS) goto fail;

        /* The channel list is sorted by name in the file; map each back to (layer, component) by name. */
        for (int ch = 0; ch < enc.channel_count && rc == EXR_ERR_SUCCESS; ++ch) {
            exr_coding_channel_info_t *ci = &enc.channels[ch];
            int found = 0;
            for (int l = 0; l < layer_count && !found; ++l) {
                for (int c = 0; c < 4 && !found; ++c) {
                    char name[EXR_MAX_LAYER_NAME + 8];
                    exr_channel_name(name, sizeof name, layers[l].name, c);
                    if (ci->channel_name && strcmp(ci->channel_name, name) == 0) {
                        size_t off = ((size_t)(cinfo.start_y) * (size_t)width) * 4u + (size_t)c;
                        ci->user_pixel_stride = 4 * (int32_t)sizeof(uint16_t);
                        ci->user_line_stride = width * 4 * (int32_t)sizeof(uint16_t);
                        ci->user_data_type = EXR_PIXEL_HALF;
                        ci->user_bytes_per_element = (int16_t)sizeof(uint16_t);
                        ci->encode_from_ptr = (const uint8_t *)(layers[l].rgba_half + off);
                        found = 1;
                    }
                }
            }
            if (!found) rc = EXR_ERR_INVALID_ARGUMENT;
        }
        stage = "encode";
        exr_compress_wrap wrap = {NULL};
        if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_choose_default_routines(ctxt, part, &enc);
        if (rc == EXR_ERR_SUCCESS && enc.compress_fn) {
            wrap.orig = enc.compress_fn;
            enc.encoding_user_data = &wrap;
            enc.compress_fn = exr_compress_no_expand;
        }
        if (rc == EXR_ERR_SUCCESS) rc = exr_encoding_run(ctxt, part, &enc);
        exr_encoding_destroy(ctxt, &enc);
        if (rc != EXR_ERR_SUCCESS) goto fail;
    }

    stage = "finish";
    rc = exr_finish(&ctxt);
    ctxt = NULL;
    if (rc != EXR_ERR_SUCCESS || stream.err_no) goto fail;

    return commit_temp(fd, tmp, path, err, err_size);

fail:
    if (ctxt) exr_finish(&ctxt);
    if (stream.err_no)
        set_err(err, err_size, "cannot write '%s': %s", p, strerror(stream.err_no));
    else
        set_err(err, err_size, "cannot write '%s': OpenEXR %s failed: %s", p, stage, exr_msg(rc));
    abort_temp(fd, tmp);
    return -1;
}

/* Our own unpack stage for the decode pipeline. OpenEXRCore 3.1.x picks specialised "interleaved" unpack
   routines by looking at the output pointers; for RGBA channels (stored sorted A,B,G,R) written into an RGBA
   buffer it picks a reversed-interleave path that returns the channels in the wrong order. The decompressed
   chunk layout is fixed by the file format (per scanline, per channel in file order, width little-endian
   values), so decode it directly. */
typedef struct exr_read_target {
    float *buf;      /* w*h RGBA floats */
    int w;           /* data window width */
    int x0, y0;      /* chunk origin relative to the data window */
    const int *comp; /* per pipeline channel: 0..3 = R,G,B,A slot, -1 = skip */
} exr_read_target;

static exr_result_t exr_unpack_rgba_float(exr_decode_pipeline_t *dec)
{
    const exr_read_target *t = (const exr_read_target *)dec->decoding_user_data;
    const uint8_t *src = (const uint8_t *)dec->unpacked_buffer;
    uint64_t avail = dec->chunk.unpacked_size, pos = 0;
    if (!t || !src) return EXR_ERR_CORRUPT_CHUNK;
    for (int ly = 0; ly < dec->chunk.height; ++ly) {
        int cury = dec->chunk.start_y + ly;
        for (int c = 0; c < dec->channel_count; ++c) {
            const exr_coding_channel_info_t *ci = &dec->channels[c];
            if (ci->height == 0 || ci->width <= 0) continue;
            if (ci->y_samples > 1 && (cury % ci->y_samples) != 0) continue;
            int bpe = ci->bytes_per_element;
            if (bpe != 2 && bpe != 4) return EXR_ERR_CORRUPT_CHUNK;
            uint64_t nbytes = (uint64_t)ci->width * (uint64_t)bpe;
            if (pos + nbytes > avail) return EXR_ERR_CORRUPT_CHUNK;
            int k = t->comp[c];
            if (k >= 0) {
                if (ci->width != dec->chunk.width || ci->height != dec->chunk.height) return EXR_ERR_CORRUPT_CHUNK;
                const uint8_t *s = src + pos;
                float *dst = t->buf + ((size_t)(t->y0 + ly) * (size_t)t->w + (size_t)t->x0) * 4u + (size_t)k;
                if (ci->data_type == EXR_PIXEL_HALF) {
                    for (int x = 0; x < ci->width; ++x, s += 2)
                        dst[4 * (size_t)x] = io_half_to_float((uint16_t)(s[0] | (s[1] << 8)));
                } else if (ci->data_type == EXR_PIXEL_FLOAT) {
                    for (int x = 0; x < ci->width; ++x, s += 4) {
                        uint32_t u = (uint32_t)s[0] | ((uint32_t)s[1] << 8) | ((uint32_t)s[2] << 16) |
                                     ((uint32_t)s[3] << 24);
                        float f;
                        memcpy(&f, &u, sizeof f);
                        dst[4 * (size_t)x] = f;
                    }
                } else {
                    return EXR_ERR_INVALID_ARGUMENT;
                }
            }
            pos += nbytes;
        }
    }
    return EXR_ERR_SUCCESS;
}

/* Opens `path` for reading just to produce an errno-based message before handing it to a library. */
static int check_readable(const char *path, char *err, size_t err_size)
{
    if (!path || !path[0]) {
        set_err(err, err_size, "cannot read '%s': empty path", safe_path(path));
        return -1;
    }
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        set_err(err, err_size, "cannot read '%s': %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    int ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    close(fd);
    if (!ok) {
        set_err(err, err_size, "cannot read '%s': not a regular file", path);
        return -1;
    }
    return 0;
}

int io_read_exr(const char *path, const char *layer_name, int *width, int *height, float **rgba, char *err,
                size_t err_size)
{
    const char *p = safe_path(path);
    if (rgba) *rgba = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    if (!width || !height || !rgba) {
        set_err(err, err_size, "cannot read '%s': NULL output argument", p);
        return -1;
    }
    if (!layer_name) layer_name = "";
    if (strlen(layer_name) > EXR_MAX_LAYER_NAME) {
        set_err(err, err_size, "cannot read '%s': layer name too long", p);
        return -1;
    }
    if (check_readable(path, err, err_size) != 0) return -1;

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_error_handler;
    exr_context_t ctxt = NULL;
    float *buf = NULL;
    int *comp = NULL; /* channel index -> RGBA slot, grown per chunk */
    int comp_cap = 0;
    exr_result_t rc;
    const char *stage = "open";
    g_exr_msg[0] = '\0';

    rc = exr_start_read(&ctxt, path, &init);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    int nparts = 0;
    rc = exr_get_count(ctxt, &nparts);
    if (rc != EXR_ERR_SUCCESS) goto fail;

    char names[4][EXR_MAX_LAYER_NAME + 8];
    for (int c = 0; c < 4; ++c) exr_channel_name(names[c], sizeof names[c], layer_name, c);

    /* Find the first part holding the layer's R, G and B channels. */
    int part = -1;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    for (int pi = 0; pi < nparts && part < 0; ++pi) {
        const exr_attr_chlist_t *chl = NULL;
        if (exr_get_storage(ctxt, pi, &storage) != EXR_ERR_SUCCESS) continue;
        if (exr_get_channels(ctxt, pi, &chl) != EXR_ERR_SUCCESS || !chl) continue;
        int have = 0;
        for (int i = 0; i < chl->num_channels; ++i) {
            for (int c = 0; c < 3; ++c) {
                if (chl->entries[i].name.str && strcmp(chl->entries[i].name.str, names[c]) == 0) have |= 1 << c;
            }
        }
        if (have != 7) continue;
        if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
            exr_finish(&ctxt);
            set_err(err, err_size, "cannot read '%s': layer '%s' is in a deep part (not supported)", p, layer_name);
            return -1;
        }
        for (int i = 0; i < chl->num_channels; ++i) {
            const exr_attr_chlist_entry_t *e = &chl->entries[i];
            for (int c = 0; c < 4; ++c) {
                if (!e->name.str || strcmp(e->name.str, names[c]) != 0) continue;
                if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT) {
                    exr_finish(&ctxt);
                    set_err(err, err_size, "cannot read '%s': channel '%s' is not HALF or FLOAT", p, names[c]);
                    return -1;
                }
                if (e->x_sampling != 1 || e->y_sampling != 1) {
                    exr_finish(&ctxt);
                    set_err(err, err_size, "cannot read '%s': channel '%s' is subsampled", p, names[c]);
                    return -1;
                }
            }
        }
        part = pi;
    }
    if (part < 0) {
        exr_finish(&ctxt);
        set_err(err, err_size, "cannot read '%s': no layer '%s' (channels %s, %s, %s)", p, layer_name, names[0],
                names[1], names[2]);
        return -1;
    }

    exr_attr_box2i_t dw;
    stage = "data window";
    rc = exr_get_data_window(ctxt, part, &dw);
    if (rc != EXR_ERR_SUCCESS) goto fail;
    int64_t w64 = (int64_t)dw.max.x - dw.min.x + 1, h64 = (int64_t)dw.max.y - dw.min.y + 1;
    if (w64 <= 0 || h64 <= 0 || w64 > IO_MAX_DIM || h64 > IO_MAX_DIM) {
        exr_finish(&ctxt);
        set_err(err, err_size, "cannot read '%s': unsupported data window %lldx%lld", p, (long long)w64,
                (long long)h64);
        return -1;
    }
    int w = (int)w64, h = (int)h64;
    size_t npix = (size_t)w * (size_t)h;
    if (npix > SIZE_MAX / (4u * sizeof(float))) {
        exr_finish(&ctxt);
        set_err(err, err_size, "cannot read '%s': image %dx%d too large", p, w, h);
        return -1;
    }
    buf = (float *)malloc(npix * 4u * sizeof(float));
    if (!buf) {
        exr_finish(&ctxt);
        set_err(err, err_size, "cannot read '%s': out of memory for %dx%d image", p, w, h);
        return -1;
    }
    for (size_t i = 0; i < npix; ++i) {
        buf[4 * i + 0] = buf[4 * i + 1] = buf[4 * i + 2] = 0.0f;
        buf[4 * i + 3] = 1.0f; /* missing A reads as 1 */
    }

    /* Chunk grid: scanline blocks, or the level-0 tiles of a tiled part. */
    int32_t step_x = w, step_y = 0;
    int64_t nx = 1, ny = 0;
    stage = "chunk layout";
    if (storage == EXR_STORAGE_SCANLINE) {
        rc = exr_get_scanlines_per_chunk(ctxt, part, &step_y);
    } else {
        uint32_t tx = 0, ty = 0;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        rc = exr_get_tile_descriptor(ctxt, part, &tx, &ty, &lm, &rm);
        if (rc == EXR_ERR_SUCCESS && (tx == 0 || ty == 0 || tx > (uint32_t)INT32_MAX || ty > (uint32_t)INT32_MAX))
            rc = EXR_ERR_INVALID_ATTR;
        step_x = (int32_t)tx;
        step_y = (int32_t)ty;
        nx = ((int64_t)w + step_x - 1) / step_x;
    }
    if (rc != EXR_ERR_SUCCESS) goto fail;
    if (step_y <= 0) {
        rc = EXR_ERR_INVALID_ATTR;
        goto fail;
    }
    ny = ((int64_t)h + step_y - 1) / step_y;

    for (int64_t cy = 0; cy < ny; ++cy) {
        for (int64_t cx = 0; cx < nx; ++cx) {
            exr_chunk_info_t cinfo;
            exr_decode_pipeline_t dec;
            memset(&cinfo, 0, sizeof cinfo);
            memset(&dec, 0, sizeof dec);
            int64_t x0, y0; /* chunk origin relative to the data window */
            stage = "chunk info";
            if (storage == EXR_STORAGE_SCANLINE) {
                rc = exr_read_scanline_chunk_info(ctxt, part, (int)(dw.min.y + cy * step_y), &cinfo);
                x0 = (int64_t)cinfo.start_x - dw.min.x;
                y0 = (int64_t)cinfo.start_y - dw.min.y;
            } else {
                rc = exr_read_tile_chunk_info(ctxt, part, (int)cx, (int)cy, 0, 0, &cinfo);
                x0 = cx * step_x; /* tile chunks report tile indices, not pixels */
                y0 = cy * step_y;
            }
            if (rc != EXR_ERR_SUCCESS) goto fail;
            if (x0 < 0 || y0 < 0 || cinfo.width <= 0 || cinfo.height <= 0 || x0 + cinfo.width > w ||
                y0 + cinfo.height > h) {
                rc = EXR_ERR_CORRUPT_CHUNK;
                goto fail;
            }
            stage = "decode init";
            rc = exr_decoding_initialize(ctxt, part, &cinfo, &dec);
            if (rc != EXR_ERR_SUCCESS) goto fail;
            if (dec.channel_count > comp_cap) {
                int *nc = (int *)realloc(comp, (size_t)dec.channel_count * sizeof(int));
                if (!nc) {
                    exr_decoding_destroy(ctxt, &dec);
                    rc = EXR_ERR_OUT_OF_MEMORY;
                    goto fail;
                }
                comp = nc;
                comp_cap = dec.channel_count;
            }
            /* Output pointers are set (the library needs them to choose its read/decompress stages) but the
               unpack stage is ours: see exr_unpack_rgba_float. */
            for (int ch = 0; ch < dec.channel_count; ++ch) {
                exr_coding_channel_info_t *ci = &dec.channels[ch];
                ci->decode_to_ptr = NULL;
                comp[ch] = -1;
                for (int c = 0; c < 4; ++c) {
                    if (ci->channel_name && strcmp(ci->channel_name, names[c]) == 0) {
                        size_t off = ((size_t)y0 * (size_t)w + (size_t)x0) * 4u + (size_t)c;
                        ci->user_pixel_stride = 4 * (int32_t)sizeof(float);
                        ci->user_line_stride = w * 4 * (int32_t)sizeof(float);
                        ci->user_data_type = EXR_PIXEL_FLOAT;
                        ci->user_bytes_per_element = (int16_t)sizeof(float);
                        ci->decode_to_ptr = (uint8_t *)(buf + off);
                        comp[ch] = c;
                    }
                }
            }
            exr_read_target target = {buf, w, (int)x0, (int)y0, comp};
            stage = "decode";
            rc = exr_decoding_choose_default_routines(ctxt, part, &dec);
            if (rc == EXR_ERR_SUCCESS) {
                dec.decoding_user_data = &target;
                dec.unpack_and_convert_fn = exr_unpack_rgba_float;
                rc = exr_decoding_run(ctxt, part, &dec);
            }
            exr_decoding_destroy(ctxt, &dec);
            if (rc != EXR_ERR_SUCCESS) goto fail;
        }
    }

    exr_finish(&ctxt);
    free(comp);
    *width = w;
    *height = h;
    *rgba = buf;
    return 0;

fail:
    if (ctxt) exr_finish(&ctxt);
    free(buf);
    free(comp);
    set_err(err, err_size, "cannot read '%s': OpenEXR %s failed: %s", p, stage, exr_msg(rc));
    return -1;
}

/* ------------------------------------------------------------------------------------------------ */
/* PNG                                                                                              */
/* ------------------------------------------------------------------------------------------------ */

typedef struct png_err_ctx {
    char msg[256];
    FILE *fp;   /* writer only */
    int err_no; /* writer only: errno of the first failed fwrite/fflush */
} png_err_ctx;

static void png_error_fn(png_structp png, png_const_charp msg)
{
    png_err_ctx *ctx = (png_err_ctx *)png_get_error_ptr(png);
    if (ctx) snprintf(ctx->msg, sizeof ctx->msg, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void png_warning_fn(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings are not errors; stay quiet */
}

/* Write callbacks that remember errno (libpng's default ones only say "Write Error"). */
static void png_write_data_fn(png_structp png, png_bytep data, size_t length)
{
    png_err_ctx *ctx = (png_err_ctx *)png_get_io_ptr(png);
    if (fwrite(data, 1, length, ctx->fp) != length) {
        if (!ctx->err_no) ctx->err_no = errno ? errno : EIO;
        png_error(png, "write error");
    }
}

static void png_flush_fn(png_structp png)
{
    png_err_ctx *ctx = (png_err_ctx *)png_get_io_ptr(png);
    if (fflush(ctx->fp) != 0) {
        if (!ctx->err_no) ctx->err_no = errno ? errno : EIO;
        png_error(png, "write error");
    }
}

int io_write_png(const char *path, int width, int height, const uint8_t *rgba8, int srgb, char *err, size_t err_size)
{
    const char *p = safe_path(path);
    if (!path || !path[0]) {
        set_err(err, err_size, "cannot write '%s': empty path", p);
        return -1;
    }
    if (width <= 0 || height <= 0 || width > IO_MAX_DIM || height > IO_MAX_DIM) {
        set_err(err, err_size, "cannot write '%s': invalid image size %dx%d", p, width, height);
        return -1;
    }
    if (!rgba8) {
        set_err(err, err_size, "cannot write '%s': no pixels", p);
        return -1;
    }

    char tmp[PATH_MAX + 64];
    int fd = open_temp(path, tmp, sizeof tmp, err, err_size);
    if (fd < 0) return -1;
    FILE *fp = fdopen(fd, "wb");
    if (!fp) {
        int e = errno;
        abort_temp(fd, tmp);
        set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }

    /* On the heap: it is changed by callbacks between setjmp and longjmp and read afterwards. */
    png_err_ctx *ectx = (png_err_ctx *)calloc(1, sizeof *ectx);
    png_structp png = NULL;
    png_infop info = NULL;
    if (ectx) {
        ectx->fp = fp;
        png = png_create_write_struct(PNG_LIBPNG_VER_STRING, ectx, png_error_fn, png_warning_fn);
        info = png ? png_create_info_struct(png) : NULL;
    }
    if (!png || !info) {
        png_destroy_write_struct(png ? &png : NULL, NULL);
        free(ectx);
        fclose(fp);
        unlink(tmp);
        set_err(err, err_size, "cannot write '%s': out of memory creating libpng writer", p);
        return -1;
    }

    /* Nothing that is modified after this point is read after a longjmp, except through png/info/fp, which
       are not modified after setjmp. */
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(fp);
        unlink(tmp);
        if (ectx->err_no)
            set_err(err, err_size, "cannot write '%s': %s", p, strerror(ectx->err_no));
        else
            set_err(err, err_size, "cannot write '%s': libpng: %s", p, ectx->msg[0] ? ectx->msg : "error");
        free(ectx);
        return -1;
    }
    png_set_write_fn(png, ectx, png_write_data_fn, png_flush_fn);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y) {
        png_write_row(png, (png_const_bytep)(rgba8 + (size_t)y * (size_t)width * 4u));
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    free(ectx);

    if (fflush(fp) != 0 || ferror(fp)) {
        int e = errno ? errno : EIO;
        fclose(fp);
        unlink(tmp);
        set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }
    if (fsync(fileno(fp)) != 0 && errno != EINVAL && errno != EROFS) {
        int e = errno;
        fclose(fp);
        unlink(tmp);
        set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }
    if (fclose(fp) != 0) {
        int e = errno;
        unlink(tmp);
        set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }
    return commit_temp(-1, tmp, path, err, err_size);
}

int io_read_png(const char *path, int *width, int *height, uint8_t **rgba8, char *err, size_t err_size)
{
    const char *p = safe_path(path);
    if (rgba8) *rgba8 = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    if (!width || !height || !rgba8) {
        set_err(err, err_size, "cannot read '%s': NULL output argument", p);
        return -1;
    }
    if (check_readable(path, err, err_size) != 0) return -1;
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        set_err(err, err_size, "cannot read '%s': %s", p, strerror(errno));
        return -1;
    }
    unsigned char sig[8];
    if (fread(sig, 1, sizeof sig, fp) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0) {
        fclose(fp);
        set_err(err, err_size, "cannot read '%s': not a PNG file", p);
        return -1;
    }

    /* On the heap: it is changed by the error callback between setjmp and longjmp and read afterwards. */
    png_err_ctx *ectx = (png_err_ctx *)calloc(1, sizeof *ectx);
    png_structp png = NULL;
    png_infop info = NULL;
    if (ectx) {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, ectx, png_error_fn, png_warning_fn);
        info = png ? png_create_info_struct(png) : NULL;
    }
    if (!png || !info) {
        png_destroy_read_struct(png ? &png : NULL, NULL, NULL);
        free(ectx);
        fclose(fp);
        set_err(err, err_size, "cannot read '%s': out of memory creating libpng reader", p);
        return -1;
    }
    /* Assigned after setjmp and needed after longjmp: volatile. */
    uint8_t *volatile pixels = NULL;
    png_bytep *volatile rows = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(fp);
        free(pixels);
        free(rows);
        set_err(err, err_size, "cannot read '%s': libpng: %s", p, ectx->msg[0] ? ectx->msg : "error");
        free(ectx);
        return -1;
    }
    png_init_io(png, fp);
    png_set_sig_bytes(png, (int)sizeof sig);
    png_set_user_limits(png, IO_MAX_DIM, IO_MAX_DIM);
    png_read_info(png, info);

    png_uint_32 w = png_get_image_width(png, info);
    png_uint_32 h = png_get_image_height(png, info);
    int color = png_get_color_type(png, info);
    int depth = png_get_bit_depth(png, info);

    if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (depth == 16) png_set_scale_16(png);
    if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
    png_set_filler(png, 0xff, PNG_FILLER_AFTER); /* no-op when alpha already present */
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)w * 4u) png_error(png, "unexpected row size after conversion");
    if ((size_t)h > SIZE_MAX / 4u / (size_t)w) png_error(png, "image too large");

    pixels = (uint8_t *)malloc((size_t)w * (size_t)h * 4u);
    rows = (png_bytep *)malloc((size_t)h * sizeof(png_bytep));
    if (!pixels || !rows) png_error(png, "out of memory");
    for (png_uint_32 y = 0; y < h; ++y) rows[y] = pixels + (size_t)y * (size_t)w * 4u;
    png_read_image(png, rows);
    png_read_end(png, NULL);

    png_destroy_read_struct(&png, &info, NULL);
    free(ectx);
    fclose(fp);
    free(rows);
    *width = (int)w;
    *height = (int)h;
    *rgba8 = pixels;
    return 0;
}
