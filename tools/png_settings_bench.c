/* png_settings_bench FILE.png [REPEATS]: what libpng's settings cost on an image (issue 27; a benchmark, not a test).
 * Re-encodes the image's RGBA8 pixels in memory with libpng (one thread) under each filter choice, zlib level and
 * strategy, and prints the CPU time (median of REPEATS, the calling thread) and the bytes; every encode is decoded
 * again and compared with the pixels, so only valid files count. vksky writes libpng's defaults: adaptive filters
 * (all five tried per row), level 6, Z_FILTERED (src/io/png_io.c; png_parallel.c keeps them). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <zlib.h>

typedef struct membuf {
    unsigned char *p;
    size_t n, cap;
} membuf;

static void mem_write(png_structp png, png_bytep data, png_size_t len)
{
    membuf *m = png_get_io_ptr(png);
    if (m->n + len > m->cap) {
        m->cap = (m->n + len) * 2;
        m->p = realloc(m->p, m->cap);
    }
    memcpy(m->p + m->n, data, len);
    m->n += len;
}
static void mem_flush(png_structp png) { (void)png; }

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* One encode: bytes into *m, CPU seconds returned. */
static double encode(membuf *m, const png_bytep px, int w, int h, int filters, int level, int strategy)
{
    m->n = 0;
    double t0 = cpu_s();
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    png_set_write_fn(png, m, mem_write, mem_flush);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (filters >= 0) png_set_filter(png, PNG_FILTER_TYPE_BASE, filters);
    png_set_compression_level(png, level);
    if (strategy >= 0) png_set_compression_strategy(png, strategy);
    png_write_info(png, info);
    for (int y = 0; y < h; ++y) png_write_row(png, px + (size_t)y * w * 4);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return cpu_s() - t0;
}

int main(int argc, char **argv)
{
    if (argc < 2) return fprintf(stderr, "usage: png_settings_bench FILE.png [REPEATS]\n"), 2;
    int repeats = argc > 2 ? atoi(argv[2]) : 5;
    if (repeats < 1 || repeats > 31) repeats = 5;
    png_image img = {.version = PNG_IMAGE_VERSION};
    if (!png_image_begin_read_from_file(&img, argv[1])) return fprintf(stderr, "cannot read %s\n", argv[1]), 2;
    img.format = PNG_FORMAT_RGBA;
    int w = (int)img.width, h = (int)img.height;
    png_bytep px = malloc(PNG_IMAGE_SIZE(img)), back = malloc(PNG_IMAGE_SIZE(img));
    if (!png_image_finish_read(&img, NULL, px, 0, NULL)) return fprintf(stderr, "cannot read %s\n", argv[1]), 2;
    static const struct { const char *name; int filters, level, strategy; } cases[] = {
        {"default: adaptive, 6, filtered", -1, 6, -1},
        {"adaptive, level 1", -1, 1, -1},
        {"adaptive, level 3", -1, 3, -1},
        {"adaptive, level 6, Z_RLE", -1, 6, Z_RLE},
        {"adaptive, level 6, Z_DEFAULT_STRATEGY", -1, 6, Z_DEFAULT_STRATEGY},
        {"none, level 6", PNG_FILTER_NONE, 6, -1},
        {"sub, level 6", PNG_FILTER_SUB, 6, -1},
        {"up, level 6", PNG_FILTER_UP, 6, -1},
        {"paeth, level 6", PNG_FILTER_PAETH, 6, -1},
        {"up, level 1", PNG_FILTER_UP, 1, -1},
        {"sub, level 1", PNG_FILTER_SUB, 1, -1},
        {"sub, level 4", PNG_FILTER_SUB, 4, -1},
        {"sub, level 6, Z_RLE", PNG_FILTER_SUB, 6, Z_RLE},
        {"sub, level 3, Z_RLE", PNG_FILTER_SUB, 3, Z_RLE},
    };
    membuf m = {0};
    printf("%s: %dx%d RGBA8, CPU s (median of %d), bytes\n", argv[1], w, h, repeats);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        double t[32];
        for (int r = 0; r < repeats; ++r)
            t[r] = encode(&m, px, w, h, cases[k].filters, cases[k].level, cases[k].strategy);
        qsort(t, (size_t)repeats, sizeof t[0], cmp_double);
        png_image dec = {.version = PNG_IMAGE_VERSION};
        int ok = png_image_begin_read_from_memory(&dec, m.p, m.n);
        dec.format = PNG_FORMAT_RGBA;
        ok = ok && png_image_finish_read(&dec, NULL, back, 0, NULL) && !memcmp(back, px, PNG_IMAGE_SIZE(img));
        printf("%-40s %.4f s %9zu bytes %s\n", cases[k].name, t[repeats / 2], m.n, ok ? "" : "(DECODE MISMATCH)");
    }
    free(m.p), free(px), free(back);
    return 0;
}
