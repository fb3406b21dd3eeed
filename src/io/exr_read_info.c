/* vksky image I/O: opening an untrusted EXR and reading its header(s): channel list, data window, camera matrices.
   See exr_read.h. Pixels are read in exr_read_pixels.c. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/exr_read_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* OpenEXRCore reports errors through a callback on the failing thread; keep the last one here instead of letting
   the library print to stderr, and put it into our one-line message. */
static _Thread_local char g_read_msg[256];

static void read_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(g_read_msg, sizeof g_read_msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

const char *io_exr_read_msg(exr_result_t rc)
{
    return g_read_msg[0] ? g_read_msg : exr_get_default_error_message(rc);
}

void io_exr_read_err(char *err, size_t err_size, const io_exr_src *src, const char *fmt, ...)
{
    if (!err || err_size == 0) return;
    int n = snprintf(err, err_size, "%s: ", src && src->label ? src->label : "(null)");
    if (n < 0) n = 0;
    if ((size_t)n < err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err + n, err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    /* One line: a file's own strings (channel names, library messages) may hold control characters. */
    for (char *p = err; *p; ++p) {
        if ((unsigned char)*p < 0x20 || *p == 0x7f) *p = ' ';
    }
}

int io_exr_src_open_file(io_exr_src *src, const char *path, char *err, size_t err_size)
{
    memset(src, 0, sizeof *src);
    src->fd = -1;
    src->label = path ? path : "(null)";
    if (!path || !path[0]) {
        io_exr_read_err(err, err_size, src, "empty path");
        return -1;
    }
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        io_exr_read_err(err, err_size, src, "cannot open: %s", strerror(errno));
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        io_exr_read_err(err, err_size, src, "not a regular file");
        return -1;
    }
    src->fd = fd;
    src->size = (uint64_t)st.st_size;
    return 0;
}

io_exr_src io_exr_src_memory(const void *data, size_t size)
{
    io_exr_src s = {"<memory>", -1, (const uint8_t *)data, (uint64_t)size};
    return s;
}

void io_exr_src_close(io_exr_src *src)
{
    if (src->fd >= 0) close(src->fd);
    src->fd = -1;
}

/* The stream callbacks: reads past the end return what is there, so the library sees a short read (and says
   so) instead of garbage. */
static int64_t src_read(exr_const_context_t ctxt, void *userdata, void *buffer, uint64_t sz, uint64_t offset,
                        exr_stream_error_func_ptr_t error_cb)
{
    const io_exr_src *s = (const io_exr_src *)userdata;
    if (offset >= s->size) return 0;
    uint64_t n = s->size - offset < sz ? s->size - offset : sz;
    if (s->fd < 0) {
        memcpy(buffer, s->data + offset, (size_t)n);
        return (int64_t)n;
    }
    uint64_t done = 0;
    while (done < n) {
        ssize_t r = pread(s->fd, (uint8_t *)buffer + done, (size_t)(n - done), (off_t)(offset + done));
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) {
            if (error_cb) error_cb(ctxt, EXR_ERR_READ_IO, "read failed: %s", strerror(errno));
            return -1;
        }
        if (r == 0) break;
        done += (uint64_t)r;
    }
    return (int64_t)done;
}

static int64_t src_size(exr_const_context_t ctxt, void *userdata)
{
    (void)ctxt;
    return (int64_t)((const io_exr_src *)userdata)->size;
}

int io_exr_src_start(const io_exr_src *src, exr_context_t *ctxt, char *err, size_t err_size)
{
    static const uint8_t magic[4] = {0x76, 0x2f, 0x31, 0x01};
    uint8_t head[4] = {0, 0, 0, 0};
    *ctxt = NULL;
    if (src_read(NULL, (void *)src, head, 4, 0, NULL) != 4 || memcmp(head, magic, 4) != 0) {
        io_exr_read_err(err, err_size, src, "not an OpenEXR file (no EXR magic number at its start)");
        return -1;
    }
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = read_error_handler;
    init.user_data = (void *)src;
    init.read_fn = src_read;
    init.size_fn = src_size;
    g_read_msg[0] = '\0';
    exr_result_t rc = exr_start_read(ctxt, src->label, &init);
    if (rc != EXR_ERR_SUCCESS) {
        if (*ctxt) exr_finish(ctxt);
        *ctxt = NULL;
        io_exr_read_err(err, err_size, src, "corrupt or unsupported EXR header: %s", io_exr_read_msg(rc));
        return -1;
    }
    return 0;
}

int io_exr_part_size(exr_context_t ctxt, const io_exr_src *src, int part, int *width, int *height, char *err,
                     size_t err_size)
{
    exr_attr_box2i_t dw;
    exr_result_t rc = exr_get_data_window(ctxt, part, &dw);
    if (rc != EXR_ERR_SUCCESS) {
        io_exr_read_err(err, err_size, src, "part %d has no data window: %s", part, io_exr_read_msg(rc));
        return -1;
    }
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    if (w <= 0 || h <= 0 || w > IO_EXR_READ_MAX_SIDE || h > IO_EXR_READ_MAX_SIDE || w * h > IO_EXR_READ_MAX_PIXELS) {
        io_exr_read_err(err, err_size, src,
                        "part %d's data window is %lldx%lld; accepted: 1 to %d pixels a side, at most %lld pixels",
                        part, (long long)w, (long long)h, IO_EXR_READ_MAX_SIDE, (long long)IO_EXR_READ_MAX_PIXELS);
        return -1;
    }
    *width = (int)w;
    *height = (int)h;
    return 0;
}

/* worldToCamera / worldToNDC: M44f as the standard says; an M44d (some writers) is narrowed to float. */
static int find_matrix(exr_context_t ctxt, int part, const char *name, float m[16])
{
    const exr_attribute_t *a = NULL;
    if (exr_get_attribute_by_name(ctxt, part, name, &a) != EXR_ERR_SUCCESS || !a) return 0;
    if (a->type == EXR_ATTR_M44F && a->m44f) {
        for (int i = 0; i < 16; ++i) m[i] = a->m44f->m[i];
        return 1;
    }
    if (a->type == EXR_ATTR_M44D && a->m44d) {
        for (int i = 0; i < 16; ++i) m[i] = (float)a->m44d->m[i];
        return 1;
    }
    return 0;
}

void io_exr_info_free(io_exr_info *info)
{
    if (!info) return;
    for (int i = 0; info->channels && i < info->channel_count; ++i) free(info->channels[i].name);
    free(info->channels);
    memset(info, 0, sizeof *info);
}

int io_exr_read_info_src(const io_exr_src *src, io_exr_info *info, char *err, size_t err_size)
{
    memset(info, 0, sizeof *info);
    exr_context_t ctxt = NULL;
    if (io_exr_src_start(src, &ctxt, err, err_size) != 0) return -1;
    int nparts = 0;
    exr_result_t rc = exr_get_count(ctxt, &nparts);
    if (rc != EXR_ERR_SUCCESS || nparts <= 0) {
        io_exr_read_err(err, err_size, src, "no parts in the file: %s", io_exr_read_msg(rc));
        goto fail;
    }
    info->part_count = nparts;
    if (io_exr_part_size(ctxt, src, 0, &info->width, &info->height, err, err_size) != 0) goto fail;

    /* Count first, so the list is allocated once at its validated size. */
    int64_t total = 0;
    for (int p = 0; p < nparts; ++p) {
        const exr_attr_chlist_t *chl = NULL;
        rc = exr_get_channels(ctxt, p, &chl);
        if (rc != EXR_ERR_SUCCESS || !chl || chl->num_channels <= 0) {
            io_exr_read_err(err, err_size, src, "part %d has no channel list: %s", p, io_exr_read_msg(rc));
            goto fail;
        }
        total += chl->num_channels;
        /* Every chunk has an 8-byte entry in the offset table: a file too short for the table cannot hold the
           image its header claims, and is refused before a caller sizes buffers by it. */
        int32_t chunks = 0;
        if (exr_get_chunk_count(ctxt, p, &chunks) == EXR_ERR_SUCCESS && (uint64_t)chunks * 8u > src->size) {
            io_exr_read_err(err, err_size, src, "truncated: part %d's chunk table needs %lld bytes, the file has %llu",
                            p, (long long)chunks * 8, (unsigned long long)src->size);
            goto fail;
        }
    }
    info->channels = (io_exr_channel *)calloc((size_t)total, sizeof *info->channels);
    if (!info->channels) {
        io_exr_read_err(err, err_size, src, "out of memory for %lld channel names", (long long)total);
        goto fail;
    }
    for (int p = 0; p < nparts; ++p) {
        const exr_attr_chlist_t *chl = NULL;
        exr_get_channels(ctxt, p, &chl);
        for (int i = 0; i < chl->num_channels; ++i) {
            const exr_attr_chlist_entry_t *e = &chl->entries[i];
            io_exr_channel *c = &info->channels[info->channel_count];
            size_t len = e->name.str && e->name.length > 0 ? (size_t)e->name.length : 0;
            c->name = (char *)malloc(len + 1);
            if (!c->name) {
                io_exr_read_err(err, err_size, src, "out of memory for channel names");
                goto fail;
            }
            if (len) memcpy(c->name, e->name.str, len);
            c->name[len] = '\0';
            c->part = p;
            c->pixel_type = (int)e->pixel_type;
            info->channel_count++;
        }
    }
    for (int p = nparts - 1; p >= 0; --p) { /* part 0 wins: searched last */
        if (find_matrix(ctxt, p, "worldToCamera", info->world_to_camera)) info->has_world_to_camera = 1;
        if (find_matrix(ctxt, p, "worldToNDC", info->world_to_ndc)) info->has_world_to_ndc = 1;
    }
    exr_finish(&ctxt);
    return 0;
fail:
    exr_finish(&ctxt);
    io_exr_info_free(info);
    return -1;
}

int io_exr_read_info(const char *path, io_exr_info *info, char *err, size_t err_size)
{
    if (!info) {
        if (err && err_size) snprintf(err, err_size, "%s: no info to fill (NULL)", path ? path : "(null)");
        return -1;
    }
    memset(info, 0, sizeof *info);
    io_exr_src src;
    if (io_exr_src_open_file(&src, path, err, err_size) != 0) return -1;
    int r = io_exr_read_info_src(&src, info, err, err_size);
    io_exr_src_close(&src);
    return r;
}
