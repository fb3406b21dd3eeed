/* vksky image I/O: the streamed PNG writer (see png_stream.h). Every libpng call sits behind its own setjmp: an
 * error in any band aborts the file, leaving nothing at the path. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/png_stream.h"
#include "io/atomic_file.h"
#include "io/encode_settings.h"
#include "io/exr_stream.h"
#include "io/io_error.h"
#include "io/png_parallel.h"

#include <errno.h>
#include <limits.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <png.h>

struct io_png_stream {
    char path[PATH_MAX], tmp[PATH_MAX + 64];
    FILE *fp;
    png_structp png;
    png_infop info;
    io_png_par *par;   /* the image data on worker threads (png_parallel.h); NULL: libpng's rows */
    int width, height, next_row;
    char msg[256];
    int err_no;
};

static void on_error(png_structp png, png_const_charp msg)
{
    io_png_stream *s = png_get_error_ptr(png);
    snprintf(s->msg, sizeof s->msg, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png, (void)msg;
}

static void on_write(png_structp png, png_bytep data, size_t length)
{
    io_png_stream *s = png_get_io_ptr(png);
    if (fwrite(data, 1, length, s->fp) != length) {
        if (!s->err_no) s->err_no = errno ? errno : EIO;
        png_error(png, "write error");
    }
}

static void on_flush(png_structp png)
{
    io_png_stream *s = png_get_io_ptr(png);
    if (fflush(s->fp) != 0) {
        if (!s->err_no) s->err_no = errno ? errno : EIO;
        png_error(png, "write error");
    }
}

static int fail(io_png_stream *s, char *err, size_t err_size)
{
    if (s->err_no) io_set_err(err, err_size, "cannot write '%s': %s", s->path, strerror(s->err_no));
    else io_set_err(err, err_size, "cannot write '%s': libpng: %s", s->path, s->msg[0] ? s->msg : "error");
    io_png_stream_abort(s);
    return -1;
}

io_png_stream *io_png_stream_open(const char *path, int width, int height, char *err, size_t err_size)
{
    if (!path || !path[0] || width < 1 || height < 1 || width > IO_STREAM_MAX_DIM || height > IO_STREAM_MAX_DIM) {
        io_set_err(err, err_size, "cannot write '%s': invalid image size %dx%d (expected 1..%d on each side)",
                   io_safe_path(path), width, height, IO_STREAM_MAX_DIM);
        return NULL;
    }
    io_png_stream *s = calloc(1, sizeof *s);
    if (!s) {
        io_set_err(err, err_size, "cannot write '%s': out of memory", path);
        return NULL;
    }
    snprintf(s->path, sizeof s->path, "%s", path);
    s->width = width, s->height = height;
    int fd = io_atomic_open(path, s->tmp, sizeof s->tmp, err, err_size);
    if (fd < 0) {
        free(s);
        return NULL;
    }
    s->fp = fdopen(fd, "wb");
    if (!s->fp) {
        s->err_no = errno;
        io_atomic_abort(fd, s->tmp);
        s->tmp[0] = '\0';
        return fail(s, err, err_size), NULL;
    }
    s->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, s, on_error, on_warning);
    s->info = s->png ? png_create_info_struct(s->png) : NULL;
    if (!s->info) {
        snprintf(s->msg, sizeof s->msg, "out of memory creating the writer");
        return fail(s, err, err_size), NULL;
    }
    if (setjmp(png_jmpbuf(s->png))) return fail(s, err, err_size), NULL;
    png_set_write_fn(s->png, s, on_write, on_flush);
    png_set_IHDR(s->png, s->info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB_ALPHA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(s->png, s->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(s->png, s->info);
    int threads = io_encode_threads();
    if (io_png_par_wanted(width, height, threads)) {
        s->par = io_png_par_create(s->fp, width, height, threads);
        if (!s->par) {
            snprintf(s->msg, sizeof s->msg, "out of memory creating the writer");
            return fail(s, err, err_size), NULL;
        }
    }
    return s;
}

/* The parallel writer's failure as the stream's. */
static int par_fail(io_png_stream *s, char *err, size_t err_size)
{
    s->err_no = io_png_par_errno(s->par);
    snprintf(s->msg, sizeof s->msg, "%s", io_png_par_message(s->par));
    return fail(s, err, err_size);
}

int io_png_stream_rows(io_png_stream *s, const uint8_t *rgba8, int rows, char *err, size_t err_size)
{
    if (rows < 0 || rows > s->height - s->next_row) {
        snprintf(s->msg, sizeof s->msg, "%d rows past the image's %d", rows, s->height);
        return fail(s, err, err_size);
    }
    if (s->par) {
        if (io_png_par_rows(s->par, rgba8, rows)) return par_fail(s, err, err_size);
        s->next_row += rows;
        return 0;
    }
    if (setjmp(png_jmpbuf(s->png))) return fail(s, err, err_size);
    for (int y = 0; y < rows; ++y) png_write_row(s->png, (png_const_bytep)(rgba8 + (size_t)y * (size_t)s->width * 4u));
    s->next_row += rows;
    return 0;
}

int io_png_stream_finish(io_png_stream *s, char *err, size_t err_size)
{
    if (s->next_row != s->height) {
        snprintf(s->msg, sizeof s->msg, "%d of %d rows given", s->next_row, s->height);
        return fail(s, err, err_size);
    }
    if (s->par) {
        if (io_png_par_finish(s->par)) return par_fail(s, err, err_size);
        io_png_par_free(s->par);
        s->par = NULL;
    } else {
        if (setjmp(png_jmpbuf(s->png))) return fail(s, err, err_size);
        png_write_end(s->png, s->info);
    }
    png_destroy_write_struct(&s->png, &s->info);
    if (fflush(s->fp) != 0 || ferror(s->fp)) {
        s->err_no = errno ? errno : EIO;
        return fail(s, err, err_size);
    }
    int fd = dup(fileno(s->fp));   /* io_atomic_commit fsyncs and closes an fd; the FILE closes its own */
    if (fd < 0 || fclose(s->fp) != 0) {
        s->err_no = errno ? errno : EIO;
        if (fd >= 0) close(fd);
        s->fp = NULL;
        return fail(s, err, err_size);
    }
    s->fp = NULL;
    int rc = io_atomic_commit(fd, s->tmp, s->path, err, err_size);
    free(s);
    return rc;
}

void io_png_stream_abort(io_png_stream *s)
{
    if (!s) return;
    io_png_par_free(s->par);
    if (s->png) png_destroy_write_struct(&s->png, s->info ? &s->info : NULL);
    if (s->fp) fclose(s->fp);
    if (s->tmp[0]) unlink(s->tmp);
    free(s);
}
