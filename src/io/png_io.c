/* vksky image I/O: PNG writer and reader (libpng). See png_io.h. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/png_io.h"

#include "io/atomic_file.h"
#include "io/encode_settings.h"
#include "io/io_error.h"
#include "io/png_parallel.h"

#include <errno.h>
#include <limits.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <png.h>

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
    const char *p = io_safe_path(path);
    if (io_check_image_target(path, width, height, err, err_size) != 0) return -1;
    if (!rgba8) {
        io_set_err(err, err_size, "cannot write '%s': no pixels", p);
        return -1;
    }

    char tmp[PATH_MAX + 64];
    int fd = io_atomic_open(path, tmp, sizeof tmp, err, err_size);
    if (fd < 0) return -1;
    FILE *fp = fdopen(fd, "wb");
    if (!fp) {
        int e = errno;
        io_atomic_abort(fd, tmp);
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
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
        io_set_err(err, err_size, "cannot write '%s': out of memory creating libpng writer", p);
        return -1;
    }

    /* Nothing that is modified after this point is read after a longjmp, except through png/info/fp, which
       are not modified after setjmp. */
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(fp);
        unlink(tmp);
        if (ectx->err_no)
            io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(ectx->err_no));
        else
            io_set_err(err, err_size, "cannot write '%s': libpng: %s", p, ectx->msg[0] ? ectx->msg : "error");
        free(ectx);
        return -1;
    }
    png_set_write_fn(png, ectx, png_write_data_fn, png_flush_fn);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    int threads = io_encode_threads();
    if (io_png_par_wanted(width, height, threads)) {
        /* The image data deflated on worker threads (png_parallel.h); libpng wrote the header chunks. */
        png_destroy_write_struct(&png, &info);
        free(ectx);
        io_png_par *par = io_png_par_create(fp, width, height, threads);
        int rc = par ? io_png_par_rows(par, rgba8, height) : -1;
        if (rc == 0) rc = io_png_par_finish(par);
        if (rc != 0) {
            if (!par) io_set_err(err, err_size, "cannot write '%s': out of memory", p);
            else if (io_png_par_errno(par)) io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(io_png_par_errno(par)));
            else io_set_err(err, err_size, "cannot write '%s': %s", p, io_png_par_message(par));
            io_png_par_free(par);
            fclose(fp);
            unlink(tmp);
            return -1;
        }
        io_png_par_free(par);
    } else {
        for (int y = 0; y < height; ++y) {
            png_write_row(png, (png_const_bytep)(rgba8 + (size_t)y * (size_t)width * 4u));
        }
        png_write_end(png, info);
        png_destroy_write_struct(&png, &info);
        free(ectx);
    }

    if (fflush(fp) != 0 || ferror(fp)) {
        int e = errno ? errno : EIO;
        fclose(fp);
        unlink(tmp);
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }
    if (fsync(fileno(fp)) != 0 && errno != EINVAL && errno != EROFS) {
        int e = errno;
        fclose(fp);
        unlink(tmp);
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }
    if (fclose(fp) != 0) {
        int e = errno;
        unlink(tmp);
        io_set_err(err, err_size, "cannot write '%s': %s", p, strerror(e));
        return -1;
    }
    return io_atomic_commit(-1, tmp, path, err, err_size);
}

int io_read_png(const char *path, int *width, int *height, uint8_t **rgba8, char *err, size_t err_size)
{
    const char *p = io_safe_path(path);
    if (rgba8) *rgba8 = NULL;
    if (width) *width = 0;
    if (height) *height = 0;
    if (!width || !height || !rgba8) {
        io_set_err(err, err_size, "cannot read '%s': NULL output argument", p);
        return -1;
    }
    if (io_check_readable(path, err, err_size) != 0) return -1;
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        io_set_err(err, err_size, "cannot read '%s': %s", p, strerror(errno));
        return -1;
    }
    unsigned char sig[8];
    if (fread(sig, 1, sizeof sig, fp) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0) {
        fclose(fp);
        io_set_err(err, err_size, "cannot read '%s': not a PNG file", p);
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
        io_set_err(err, err_size, "cannot read '%s': out of memory creating libpng reader", p);
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
        io_set_err(err, err_size, "cannot read '%s': libpng: %s", p, ectx->msg[0] ? ectx->msg : "error");
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
