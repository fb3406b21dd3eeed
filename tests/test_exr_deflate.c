/* EXR ZIP/ZIPS chunks through libdeflate and the chunk pool (src/io/exr_deflate.c, exr_parallel.c; issue 27).
 * Checked against computations that do not use them:
 *  - the predictor equals the OpenEXR file format's (written here from the spec: even bytes, then odd ones, then each
 *    byte minus the one before plus 128), for even and odd lengths;
 *  - a compressed chunk inflates with zlib (not libdeflate) and, un-predicted by the spec's inverse, gives back the
 *    packed bytes; data that does not compress (noise, one byte) is stored raw, as every reader expects;
 *  - the default level (unset) writes level 4's stream, not level 6's (OpenEXR 3.2's default), and on a sky-like
 *    chunk is within 10 % of zlib's level 4: a wrong level or a stored stream would miss it;
 *  - whole files (float and half, ZIP and ZIPS, zlib levels 1 and 9) written with 1, 3 and 8 threads are the same
 *    bytes, and OpenEXRCore (zlib inflating) reads back the pixels of the same image written uncompressed;
 *  - the streamed writer (one pool over every band) fed bands of 5, 16 and 37 rows with 1 and 4 threads writes the
 *    same bytes each time and the same pixels;
 *  - a streamed write failing half-way (RLIMIT_FSIZE) with 4 threads fails with EFBIG and leaves no file (the pool
 *    stops, nothing hangs);
 *  - io_exr_compression_lines (the chunk height a banded writer rounds its bands to before the file exists) equals
 *    what OpenEXRCore itself gives a part of each compression (exr_get_scanlines_per_chunk).
 * `test_exr_deflate bench FILE.exr [REPEATS]` times zlib (compress2, as OpenEXR 3.1) against libdeflate on the
 * file's ZIP chunks instead: a benchmark, not a test. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "io/encode_settings.h"
#include "io/exr_deflate.h"
#include "io/exr_read.h"
#include "io/exr_stream.h"
#include "io/exr_write.h"
#include "check.h"
#include "file_bench.h"

#include <errno.h>
#include <libdeflate.h>
#include <signal.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

static char dir[] = "/tmp/vksky_exrdeflate.XXXXXX";

/* The spec's predictor, and its inverse. */
static void spec_predict(uint8_t *out, const uint8_t *raw, size_t n)
{
    uint8_t *tmp = malloc(n + 1);
    size_t k = 0;
    for (size_t i = 0; i < n; i += 2) tmp[k++] = raw[i];
    for (size_t i = 1; i < n; i += 2) tmp[k++] = raw[i];
    for (size_t i = 0; i < n; ++i) out[i] = i == 0 ? tmp[0] : (uint8_t)((tmp[i] - tmp[i - 1] + 128) & 255);
    free(tmp);
}

static void spec_unpredict(uint8_t *raw, const uint8_t *in, size_t n)
{
    uint8_t *tmp = malloc(n + 1);
    for (size_t i = 0; i < n; ++i) tmp[i] = i == 0 ? in[0] : (uint8_t)((tmp[i - 1] + in[i] - 128) & 255);
    size_t half = (n + 1) / 2;
    for (size_t i = 0; i < n; ++i) raw[i] = (i % 2 == 0) ? tmp[i / 2] : tmp[half + i / 2];
    free(tmp);
}

static uint32_t rng = 2463534242u;
static uint32_t next_rand(void) { return rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5; }

/* A sky-like RGBA float image: smooth gradients, a little noise, a bright disc. */
static float *make_sky(int w, int h)
{
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float *p = px + ((size_t)y * w + x) * 4;
            float n = (float)(next_rand() % 1000) * 1e-6f;
            float dx = (float)(x - w / 3), dy = (float)(y - h / 4);
            float sun = dx * dx + dy * dy < 9.0f ? 1.6e9f : 0.0f;
            p[0] = 2000.0f + 3000.0f * (float)y / (float)h + n + sun;
            p[1] = 4000.0f + 1500.0f * (float)x / (float)w + n + sun;
            p[2] = 9000.0f - 2000.0f * (float)y / (float)h + sun;
            p[3] = 1.0f;
        }
    return px;
}

/* One chunk as OpenEXR packs it: per scanline, the channels in name order (A, B, G, R), each a row of floats. */
static uint8_t *pack_chunk(const float *rgba, int w, int y0, int rows, size_t *n)
{
    *n = (size_t)rows * 4 * (size_t)w * sizeof(float);
    uint8_t *out = malloc(*n);
    uint8_t *o = out;
    static const int order[4] = {3, 2, 1, 0};
    for (int y = y0; y < y0 + rows; ++y)
        for (int c = 0; c < 4; ++c)
            for (int x = 0; x < w; ++x, o += 4) memcpy(o, &rgba[((size_t)y * w + x) * 4 + order[c]], 4);
    return out;
}

static void *t_alloc(exr_transcoding_pipeline_buffer_id_t id, size_t n) { (void)id; return malloc(n); }
static void t_free(exr_transcoding_pipeline_buffer_id_t id, void *p) { (void)id; free(p); }

/* io_exr_deflate_chunk on `raw`; the pipeline's buffers returned in *enc (free with free_pipe). */
static exr_result_t deflate_raw(exr_encode_pipeline_t *enc, struct libdeflate_compressor *c, uint8_t *raw, size_t n)
{
    memset(enc, 0, sizeof *enc);
    enc->packed_buffer = raw, enc->packed_bytes = n, enc->alloc_fn = t_alloc, enc->free_fn = t_free;
    return io_exr_deflate_chunk(enc, c);
}

static void free_pipe(exr_encode_pipeline_t *enc) { free(enc->compressed_buffer), free(enc->scratch_buffer_1); }

static void check_predictor(void)
{
    size_t sizes[] = {1, 2, 3, 4, 5, 16, 17, 1023, 4096};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
        size_t n = sizes[k];
        uint8_t *raw = malloc(n), *a = malloc(n), *b = malloc(n);
        for (size_t i = 0; i < n; ++i) raw[i] = (uint8_t)next_rand();
        spec_predict(a, raw, n);
        io_exr_zip_predict(b, raw, n);
        CHECK(memcmp(a, b, n) == 0, "predictor differs from the spec's at %zu bytes", n);
        free(raw), free(a), free(b);
    }
}

static void check_chunks(void)
{
    struct libdeflate_compressor *c = io_exr_deflate_alloc(-1);
    CHECK(c != NULL, "no compressor");
    int w = 331, rows = 16;
    float *sky = make_sky(w, rows);
    size_t n = 0;
    uint8_t *raw = pack_chunk(sky, w, 0, rows, &n);
    exr_encode_pipeline_t enc;
    CHECK(deflate_raw(&enc, c, raw, n) == EXR_ERR_SUCCESS, "sky chunk");
    CHECK(enc.compressed_bytes < n, "a sky chunk should compress (%zu of %zu bytes)", (size_t)enc.compressed_bytes, n);
    /* zlib inflates it; the spec's inverse predictor gives the packed bytes back. */
    uint8_t *inflated = malloc(n), *back = malloc(n);
    uLongf got = (uLongf)n;
    CHECK(uncompress(inflated, &got, enc.compressed_buffer, (uLong)enc.compressed_bytes) == Z_OK && got == n,
          "zlib cannot inflate the chunk (%lu of %zu bytes)", (unsigned long)got, n);
    spec_unpredict(back, inflated, n);
    CHECK(memcmp(back, raw, n) == 0, "the chunk does not round-trip");
    /* The default (-1, unset) is level 4, OpenEXR 3.2's EXR_DEFAULT_ZLIB_COMPRESS_LEVEL: the same stream as asking
     * for 4, and a different one from 6 (else the default would not be 4). */
    exr_encode_pipeline_t enc4, enc6;
    struct libdeflate_compressor *c4 = io_exr_deflate_alloc(4), *c6 = io_exr_deflate_alloc(6);
    CHECK(deflate_raw(&enc4, c4, raw, n) == EXR_ERR_SUCCESS && deflate_raw(&enc6, c6, raw, n) == EXR_ERR_SUCCESS,
          "sky chunk at 4 and 6");
    CHECK(enc4.compressed_bytes == enc.compressed_bytes &&
              !memcmp(enc4.compressed_buffer, enc.compressed_buffer, enc.compressed_bytes),
          "the default level's chunk differs from level 4's");
    CHECK(enc6.compressed_bytes != enc4.compressed_bytes ||
              memcmp(enc6.compressed_buffer, enc4.compressed_buffer, enc4.compressed_bytes),
          "levels 4 and 6 wrote the same chunk: the level is not applied");
    /* zlib at the same level on the same predicted bytes (what OpenEXR 3.1 would store at zip:4): within 10 %. */
    uint8_t *pred = malloc(n), *z = malloc(compressBound((uLong)n));
    spec_predict(pred, raw, n);
    uLongf zn = compressBound((uLong)n);
    CHECK(compress2(z, &zn, pred, (uLong)n, 4) == Z_OK, "zlib compress2");
    CHECK((double)enc.compressed_bytes <= 1.10 * (double)zn, "libdeflate 4: %zu bytes, zlib 4: %lu",
          (size_t)enc.compressed_bytes, (unsigned long)zn);
    free_pipe(&enc), free_pipe(&enc4), free_pipe(&enc6);
    io_exr_deflate_free(c4), io_exr_deflate_free(c6);
    /* Noise and a single byte: stored raw (compressed_bytes == packed_bytes, the same bytes). */
    for (size_t i = 0; i < n; ++i) raw[i] = (uint8_t)next_rand();
    CHECK(deflate_raw(&enc, c, raw, n) == EXR_ERR_SUCCESS, "noise chunk");
    CHECK(enc.compressed_bytes == n && memcmp(enc.compressed_buffer, raw, n) == 0, "noise should be stored raw");
    free_pipe(&enc);
    CHECK(deflate_raw(&enc, c, raw, 1) == EXR_ERR_SUCCESS && enc.compressed_bytes == 1, "one byte stored raw");
    free_pipe(&enc);
    free(sky), free(raw), free(inflated), free(back), free(pred), free(z);
    io_exr_deflate_free(c);
}

static void settings(int compression, int level, int threads)
{
    io_encode_settings s = {.threads = threads, .exr_compression = compression, .zip_level = level};
    io_encode_settings_set(&s);
}

static bool same_pixels(const char *a, const char *b, int w, int h)
{
    char err[512];
    int wa, ha, wb, hb;
    float *pa = NULL, *pb = NULL;
    bool ok = io_read_exr(a, "", &wa, &ha, &pa, err, sizeof err) == 0 && io_read_exr(b, "", &wb, &hb, &pb, err,
                                                                                     sizeof err) == 0;
    if (!ok) fprintf(stderr, "%s\n", err);
    ok = ok && wa == w && ha == h && wb == w && hb == h && memcmp(pa, pb, (size_t)w * h * 4 * sizeof(float)) == 0;
    free(pa), free(pb);
    return ok;
}

/* A streamed file fed bands of `band` rows. */
static int write_stream(const char *path, const float *sky, int w, int h, int band, bool store_float)
{
    char err[512];
    io_exr_stream *s = io_exr_stream_open_f32(path, w, h, NULL, store_float, err, sizeof err);
    if (!s) return fprintf(stderr, "%s\n", err), -1;
    for (int y = 0; y < h; y += band) {
        /* A copy per band, scribbled over once handed in: the stream must not read a band after it returns. */
        int rows = h - y < band ? h - y : band;
        size_t n = (size_t)rows * w * 4;
        float *copy = malloc(n * sizeof(float));
        memcpy(copy, sky + (size_t)y * w * 4, n * sizeof(float));
        if (io_exr_stream_rows_f32(s, copy, rows, err, sizeof err) != 0) return free(copy), fprintf(stderr, "%s\n", err), -1;
        for (size_t i = 0; i < n; ++i) copy[i] = -1.0f;
        free(copy);
    }
    return io_exr_stream_finish(s, err, sizeof err) == 0 ? 0 : (fprintf(stderr, "%s\n", err), -1);
}

static void check_files(void)
{
    int w = 97, h = 53;   /* odd: the last chunk is short */
    float *sky = make_sky(w, h);
    char err[512], ref[600], path[600], first[600];
    static const struct { int comp, level; const char *name; } cases[] = {
        {EXR_COMPRESSION_ZIP, 0, "zip"}, {EXR_COMPRESSION_ZIPS, 0, "zips"}, {EXR_COMPRESSION_ZIP, 1, "zip1"},
        {EXR_COMPRESSION_ZIP, 9, "zip9"}, {EXR_COMPRESSION_ZIP, 4, "zip4"}};
    static const int threads[] = {1, 3, 8};
    for (int store_float = 0; store_float < 2; ++store_float) {
        snprintf(ref, sizeof ref, "%s/none%d.exr", dir, store_float);
        settings(EXR_COMPRESSION_NONE, 0, 1);
        CHECK(io_write_exr_rgba_f32(ref, w, h, sky, store_float, NULL, err, sizeof err) == 0, "%s", err);
        for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k)
            for (size_t t = 0; t < sizeof threads / sizeof threads[0]; ++t) {
                snprintf(path, sizeof path, "%s/%s_%d_%d.exr", dir, cases[k].name, store_float, threads[t]);
                if (t == 0) snprintf(first, sizeof first, "%s", path);
                settings(cases[k].comp, cases[k].level, threads[t]);
                CHECK(io_write_exr_rgba_f32(path, w, h, sky, store_float, NULL, err, sizeof err) == 0, "%s", err);
                CHECK(same_pixels(path, ref, w, h), "%s: pixels differ from the uncompressed file", path);
                CHECK(same_file(path, first), "%s: bytes differ from 1 thread's", path);
            }
        /* No level asked for is zip:4 (the default level), byte for byte. */
        char dflt[600];
        snprintf(dflt, sizeof dflt, "%s/zip_%d_1.exr", dir, store_float);
        snprintf(path, sizeof path, "%s/zip4_%d_1.exr", dir, store_float);
        CHECK(same_file(dflt, path), "zip (default level) and zip:4 differ");
        /* Streamed: one pool over every band; bytes the same for every band size and thread count. */
        static const int bands[] = {5, 16, 37};
        for (size_t b = 0; b < 3; ++b)
            for (int tc = 1; tc <= 4; tc += 3) {
                snprintf(path, sizeof path, "%s/stream_%d_%d_%d.exr", dir, store_float, bands[b], tc);
                if (b == 0 && tc == 1) snprintf(first, sizeof first, "%s", path);
                settings(EXR_COMPRESSION_ZIP, 0, tc);
                CHECK(write_stream(path, sky, w, h, bands[b], store_float) == 0, "stream %s", path);
                CHECK(same_pixels(path, ref, w, h), "%s: pixels differ from the uncompressed file", path);
                CHECK(same_file(path, first), "%s: bytes differ from 5-row bands, 1 thread", path);
            }
    }
    free(sky);
}

static void check_write_failure(void)
{
    int w = 512, h = 400;   /* float noise: ~3 MB, far past the limit */
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    for (size_t i = 0; i < (size_t)w * h * 4; ++i) px[i] = (float)next_rand();
    char path[600], err[512] = "";
    snprintf(path, sizeof path, "%s/full.exr", dir);
    settings(EXR_COMPRESSION_ZIP, 0, 4);
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old, lim.rlim_cur = 100000;
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    if (setrlimit(RLIMIT_FSIZE, &lim) == 0) {
        io_exr_stream *s = io_exr_stream_open_f32(path, w, h, NULL, true, err, sizeof err);
        int rc = s ? 0 : -1;
        for (int y = 0; y < h && rc == 0; y += 37)
            rc = io_exr_stream_rows_f32(s, px + (size_t)y * w * 4, h - y < 37 ? h - y : 37, err, sizeof err);
        if (rc == 0) rc = io_exr_stream_finish(s, err, sizeof err);
        setrlimit(RLIMIT_FSIZE, &old);
        CHECK(rc == -1 && strstr(err, strerror(EFBIG)), "a write past RLIMIT_FSIZE: rc %d, '%s'", rc, err);
        CHECK(access(path, F_OK) != 0, "a failed write left %s", path);
    }
    signal(SIGXFSZ, prev);
    free(px);
}

/* CPU seconds (median of `repeats`) and bytes to compress every 16-row chunk of `rgba`, float channels: zlib's
 * compress2 or libdeflate at `level`, the predictor included (both writers run it). */
static void bench_one(const float *rgba, int w, int h, int level, bool use_zlib, int repeats, double *s, size_t *bytes)
{
    double t[32];
    struct libdeflate_compressor *c = use_zlib ? NULL : io_exr_deflate_alloc(level);
    for (int r = 0; r < repeats; ++r) {
        double sum = 0.0;
        *bytes = 0;
        for (int y = 0; y < h; y += 16) {
            size_t n = 0;
            uint8_t *raw = pack_chunk(rgba, w, y, h - y < 16 ? h - y : 16, &n);
            double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
            if (use_zlib) {
                uint8_t *pred = malloc(n), *z = malloc(compressBound((uLong)n));
                uLongf zn = compressBound((uLong)n);
                io_exr_zip_predict(pred, raw, n);
                compress2(z, &zn, pred, (uLong)n, level);
                *bytes += zn < n ? zn : n;
                free(pred), free(z);
            } else {
                exr_encode_pipeline_t enc;
                deflate_raw(&enc, c, raw, n);
                *bytes += enc.compressed_bytes;
                free_pipe(&enc);
            }
            sum += clock_s(CLOCK_THREAD_CPUTIME_ID) - t0;
            free(raw);
        }
        t[r] = sum;
    }
    qsort(t, (size_t)repeats, sizeof t[0], cmp_double);
    *s = t[repeats / 2];
    io_exr_deflate_free(c);
}

static int bench(const char *file, int repeats)
{
    char err[512];
    int w, h;
    float *rgba = NULL;
    if (io_read_exr(file, "", &w, &h, &rgba, err, sizeof err) != 0) return fprintf(stderr, "%s\n", err), 2;
    printf("%s: %dx%d float RGBA, %d chunks of 16 rows, CPU s (median of %d) and MB for all chunks, one thread\n",
           file, w, h, (h + 15) / 16, repeats);
    printf("level  zlib_s  zlib_MB  libdeflate_s  libdeflate_MB  speed-up\n");
    static const int levels[] = {1, 4, 6, 9};
    for (int k = 0; k < 4; ++k) {
        double zs, ds;
        size_t zb, db;
        bench_one(rgba, w, h, levels[k], true, repeats, &zs, &zb);
        bench_one(rgba, w, h, levels[k], false, repeats, &ds, &db);
        printf("%5d  %6.4f  %7.3f  %12.4f  %13.3f  %7.2fx\n", levels[k], zs, zb / 1e6, ds, db / 1e6, zs / ds);
    }
    /* The predictor alone (both columns above include it). */
    double t[32];
    for (int r = 0; r < repeats; ++r) {
        t[r] = 0.0;
        for (int y = 0; y < h; y += 16) {
            size_t n = 0;
            uint8_t *raw = pack_chunk(rgba, w, y, h - y < 16 ? h - y : 16, &n), *pred = malloc(n);
            double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
            io_exr_zip_predict(pred, raw, n);
            t[r] += clock_s(CLOCK_THREAD_CPUTIME_ID) - t0;
            free(raw), free(pred);
        }
    }
    qsort(t, (size_t)repeats, sizeof t[0], cmp_double);
    printf("predictor alone: %.4f s\n", t[repeats / 2]);
    free(rgba);
    return 0;
}

static void check_chunk_lines(void)
{
    char path[600];
    snprintf(path, sizeof path, "%s/lines.exr", dir);
    for (int c = EXR_COMPRESSION_NONE; c < EXR_COMPRESSION_LAST_TYPE; ++c) {
        /* OpenEXR 3.1 can name DWAA/DWAB but not write them (0 lines): the writers refuse them there anyway. */
        if (!io_exr_compression_writable(c)) continue;
        exr_context_t ctxt = NULL;
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        int part = -1;
        int32_t lines = -1;
        exr_result_t rc = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
        if (rc == EXR_ERR_SUCCESS) rc = exr_add_part(ctxt, "", EXR_STORAGE_SCANLINE, &part);
        if (rc == EXR_ERR_SUCCESS) rc = exr_initialize_required_attr_simple(ctxt, part, 8, 8, (exr_compression_t)c);
        if (rc == EXR_ERR_SUCCESS) rc = exr_add_channel(ctxt, part, "Y", EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
        /* The chunk layout is known once the header is written (as the streamed writer asks it). */
        if (rc == EXR_ERR_SUCCESS) rc = exr_write_header(ctxt);
        if (rc == EXR_ERR_SUCCESS) rc = exr_get_scanlines_per_chunk(ctxt, part, &lines);
        CHECK(rc == EXR_ERR_SUCCESS, "compression %d: OpenEXRCore gives no chunk height (%d)", c, (int)rc);
        CHECK(rc != EXR_ERR_SUCCESS || io_exr_compression_lines(c) == lines,
              "compression %s: io_exr_compression_lines %d, OpenEXRCore %d", io_exr_compression_name(c),
              io_exr_compression_lines(c), (int)lines);
        if (ctxt) exr_finish(&ctxt);
        remove(path);
    }
}

int main(int argc, char **argv)
{
    if (argc >= 3 && !strcmp(argv[1], "bench")) {
        int r = argc >= 4 ? atoi(argv[3]) : 5;
        return bench(argv[2], r < 1 ? 1 : r > 31 ? 31 : r);
    }
    if (!mkdtemp(dir)) return perror("mkdtemp"), 1;
    check_predictor();
    check_chunks();
    check_files();
    check_write_failure();
    check_chunk_lines();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return check_report("exr_deflate");
}
