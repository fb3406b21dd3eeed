/* The parallel PNG writer (src/io/png_parallel.c, issue 27). Checks, against computations that do not use it:
 *  - --threads 1 writes exactly what libpng writes by itself (this test drives libpng directly: today's bytes);
 *  - 2, 3 and 8 threads write the same bytes as each other, and the streamed writer handing rows over in odd band
 *    sizes writes those bytes too (the blocks do not depend on threads or batching);
 *  - the file decodes to the source pixels with libpng, with zlib inflating the IDAT stream on its own (the stream
 *    ends where it should and its Adler-32 holds; every chunk's CRC), and with OpenImageIO (idiff: no difference
 *    from libpng's own file), for a tall image, a single-row-per-block wide one and a short one (libpng's path);
 *  - a write failing half-way (RLIMIT_FSIZE) leaves no file.
 * `test_png_parallel bench W H [REPEATS]` prints encode medians by thread count instead (a benchmark, not a test). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/encode_settings.h"
#include "io/png_io.h"
#include "io/png_stream.h"
#include "check.h"
#include "file_bench.h"

#include <dirent.h>
#include <errno.h>
#include <png.h>
#include <signal.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

static char dir[] = "/tmp/vksky_pngpar.XXXXXX";

/* A sky-like image: smooth gradients (what filters and deflate like) with a little noise and a hard edge. */
static uint8_t *make_image(int w, int h)
{
    uint8_t *px = malloc((size_t)w * h * 4);
    uint32_t s = 12345;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            s = s * 1664525u + 1013904223u;
            uint8_t *p = px + ((size_t)y * w + x) * 4;
            int n = (int)(s >> 29);
            p[0] = (uint8_t)(40 + 150 * y / h + n), p[1] = (uint8_t)(90 + 100 * x / w), p[2] = (uint8_t)(200 - n);
            p[3] = y > h * 3 / 4 ? 255 : (uint8_t)(x * 7);
        }
    return px;
}

/* libpng alone, as png_io.c sets it up: RGBA8, sRGB chunk, default compression and filters. */
static void libpng_write(const char *path, int w, int h, const uint8_t *px)
{
    FILE *f = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        CHECK(0, "libpng failed writing %s", path);
        fclose(f);
        return;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < h; ++y) png_write_row(png, px + (size_t)y * w * 4);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    fclose(f);
}

/* Walks the chunks (CRCs), inflates the IDATs with zlib alone and unfilters them; compares with px. */
static void zlib_check(const char *path, int w, int h, const uint8_t *px, int *idat_count)
{
    size_t n = 0;
    uint8_t *d = slurp(path, &n);
    size_t row = (size_t)w * 4 + 1, raw_len = row * h;
    uint8_t *raw = malloc(raw_len + 1);
    z_stream z = {0};
    inflateInit(&z);
    z.next_out = raw, z.avail_out = (uInt)raw_len + 1;
    int zrc = Z_OK, chunks = 0;
    bool crc_ok = true, iend = false;
    for (size_t i = 8; d && i + 12 <= n;) {
        uint32_t len = (uint32_t)d[i] << 24 | (uint32_t)d[i + 1] << 16 | (uint32_t)d[i + 2] << 8 | d[i + 3];
        if (i + 12 + len > n) break;
        uint32_t crc = (uint32_t)d[i + 8 + len] << 24 | (uint32_t)d[i + 9 + len] << 16 |
                       (uint32_t)d[i + 10 + len] << 8 | d[i + 11 + len];
        crc_ok &= crc == (uint32_t)crc32(0, d + i + 4, len + 4);
        if (!memcmp(d + i + 4, "IDAT", 4)) {
            ++chunks;
            z.next_in = d + i + 8, z.avail_in = len;
            if (zrc == Z_OK) zrc = inflate(&z, Z_NO_FLUSH);
        }
        if (!memcmp(d + i + 4, "IEND", 4)) iend = i + 12 == n;
        i += 12 + len;
    }
    *idat_count = chunks;
    CHECK(crc_ok, "%s: a chunk's CRC is wrong", path);
    CHECK(iend, "%s: no IEND at the end", path);
    CHECK(zrc == Z_STREAM_END && z.total_out == raw_len, "%s: zlib: %d after %lu of %zu bytes (Adler-32 checked)",
          path, zrc, z.total_out, raw_len);
    inflateEnd(&z);
    bool same = zrc == Z_STREAM_END;
    for (int y = 0; y < h && same; ++y) {
        uint8_t *r = raw + row * y, *up = y ? raw + row * (y - 1) : NULL;   /* byte 0: the filter type */
        for (size_t i = 1; i < row; ++i) {
            int a = i > 4 ? r[i - 4] : 0, b = up ? up[i] : 0, c = up && i > 4 ? up[i - 4] : 0;
            int pv = a + b - c, pa = abs(pv - a), pb = abs(pv - b), pc = abs(pv - c);
            int pred = r[0] == 0 ? 0 : r[0] == 1 ? a : r[0] == 2 ? b : r[0] == 3 ? (a + b) / 2
                     : pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            r[i] = (uint8_t)(r[i] + pred);
        }
        same = r[0] <= 4 && memcmp(r + 1, px + (size_t)y * w * 4, (size_t)w * 4) == 0;
    }
    CHECK(same, "%s: zlib + unfiltering does not give the source pixels", path);
    free(raw);
    free(d);
}

static void set_threads(int t)
{
    io_encode_settings s = io_encode_settings_get();
    s.threads = t;
    io_encode_settings_set(&s);
}

static void check_size(int w, int h, bool parallel_expected)
{
    char ref[512], p1[512], pn[512], ps[512], err[512], cmd[1200];
    snprintf(ref, sizeof ref, "%s/libpng_%dx%d.png", dir, w, h);
    snprintf(p1, sizeof p1, "%s/t1_%dx%d.png", dir, w, h);
    uint8_t *px = make_image(w, h);
    libpng_write(ref, w, h, px);
    set_threads(1);
    CHECK(io_write_png(p1, w, h, px, 1, err, sizeof err) == 0, "%s", err);
    CHECK(same_file(ref, p1), "%dx%d: --threads 1 is not libpng's own bytes", w, h);
    char first[512] = "";
    int threads[] = {2, 3, 8};
    for (int k = 0; k < 3; ++k) {
        set_threads(threads[k]);
        snprintf(pn, sizeof pn, "%s/t%d_%dx%d.png", dir, threads[k], w, h);
        CHECK(io_write_png(pn, w, h, px, 1, err, sizeof err) == 0, "%s", err);
        if (!first[0]) snprintf(first, sizeof first, "%s", pn);
        else CHECK(same_file(first, pn), "%dx%d: %d threads differ from 2", w, h, threads[k]);
    }
    CHECK(same_file(ref, first) == !parallel_expected, "%dx%d: parallel path %s expected", w, h,
          parallel_expected ? "" : "not");
    /* The streamed writer, rows in bands of 1, 7, 333, ... rows: the same bytes. */
    set_threads(3);
    snprintf(ps, sizeof ps, "%s/stream_%dx%d.png", dir, w, h);
    io_png_stream *s = io_png_stream_open(ps, w, h, err, sizeof err);
    CHECK(s != NULL, "%s", err);
    int bands[] = {1, 7, 333, 2, 64, 1000}, y = 0;
    for (int b = 0; s && y < h; ++b) {
        int n = bands[b % 6] < h - y ? bands[b % 6] : h - y;
        if (io_png_stream_rows(s, px + (size_t)y * w * 4, n, err, sizeof err)) s = NULL;
        y += n;
    }
    CHECK(s && io_png_stream_finish(s, err, sizeof err) == 0, "stream: %s", err);
    CHECK(same_file(first, ps), "%dx%d: streamed bands differ from the whole image", w, h);
    /* Decoders: libpng (io_read_png), zlib alone, OpenImageIO. */
    int rw = 0, rh = 0, idats = 0;
    uint8_t *back = NULL;
    CHECK(io_read_png(first, &rw, &rh, &back, err, sizeof err) == 0, "%s", err);
    CHECK(back && rw == w && rh == h && !memcmp(back, px, (size_t)w * h * 4), "%dx%d: libpng decodes other pixels",
          w, h);
    free(back);
    zlib_check(first, w, h, px, &idats);
    if (parallel_expected) CHECK(idats >= 2, "%dx%d: %d IDAT chunks: the image was not cut into blocks", w, h, idats);
    snprintf(cmd, sizeof cmd, "idiff -q -fail 0 -failpercent 0 -warn 0 '%s' '%s' >/dev/null 2>&1", ref, first);
    int rc = system(cmd);
    CHECK(rc == 0, "%dx%d: OpenImageIO (idiff) sees a difference from libpng's file (status %d)", w, h, rc);
    free(px);
}

static int bench(int w, int h, int repeats)
{
    uint8_t *px = make_image(w, h);
    char path[512], err[512];
    snprintf(path, sizeof path, "%s/bench.png", dir);
    int threads[] = {1, 2, 4, 8, 16};
    for (int k = 0; k < 5; ++k) {
        set_threads(threads[k]);
        double t[32], cpu[32];   /* wall and the process's CPU seconds (all threads) per encode */
        io_write_png(path, w, h, px, 1, err, sizeof err);   /* warm-up */
        for (int i = 0; i < repeats; ++i) {
            double t0 = clock_s(CLOCK_MONOTONIC), c0 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
            if (io_write_png(path, w, h, px, 1, err, sizeof err)) return fprintf(stderr, "%s\n", err), 1;
            t[i] = clock_s(CLOCK_MONOTONIC) - t0, cpu[i] = clock_s(CLOCK_PROCESS_CPUTIME_ID) - c0;
        }
        qsort(t, (size_t)repeats, sizeof t[0], cmp_double);
        qsort(cpu, (size_t)repeats, sizeof cpu[0], cmp_double);
        size_t n = 0;
        free(slurp(path, &n));
        printf("png_encode %dx%d threads %d median_s %.4f cpu_s %.4f mpix_per_s %.1f bytes %zu\n", w, h, threads[k],
               t[repeats / 2], cpu[repeats / 2], (double)w * h / 1e6 / t[repeats / 2], n);
    }
    free(px);
    return 0;
}

int main(int argc, char **argv)
{
    if (!mkdtemp(dir)) return perror("mkdtemp"), 1;
    if (argc >= 4 && !strcmp(argv[1], "bench")) {
        int r = argc > 4 ? atoi(argv[4]) : 5;
        int rc = bench(atoi(argv[2]), atoi(argv[3]), r < 1 ? 1 : r > 32 ? 32 : r);
        char cmd[600];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
        return system(cmd) != 0 || rc;
    }
    check_size(640, 400, true);     /* 2560-byte rows: 102 rows a block, 4 blocks, the last short */
    check_size(65536, 3, true);     /* rows longer than a block: a block per row */
    check_size(64, 48, false);      /* one block: libpng writes it whatever the threads */

    /* A write failing half-way through the parallel path: -1, the errno named, no file and no temp file. */
    int w = 640, h = 400;
    uint8_t *px = make_image(w, h);
    char path[512], err[512] = "";
    snprintf(path, sizeof path, "%s/full.png", dir);
    set_threads(4);
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old, lim.rlim_cur = 100000;
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    if (setrlimit(RLIMIT_FSIZE, &lim) == 0) {
        int rc = io_write_png(path, w, h, px, 1, err, sizeof err);
        setrlimit(RLIMIT_FSIZE, &old);
        CHECK(rc == -1 && strstr(err, strerror(EFBIG)), "a write past RLIMIT_FSIZE: rc %d, '%s'", rc, err);
        CHECK(access(path, F_OK) != 0, "a failed write left %s", path);
        DIR *d = opendir(dir);
        int left = 0;
        for (struct dirent *e; d && (e = readdir(d));) left += strstr(e->d_name, "full") != NULL;
        if (d) closedir(d);
        CHECK(left == 0, "a failed write left %d temp file(s) in %s", left, dir);
    }
    signal(SIGXFSZ, prev);
    free(px);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return check_report("png_parallel");
}
