/* Standalone test for src/io/ (exr_write, exr_read, png_io, atomic_file, half_float). Exits non-zero on any failure.
 *
 * Covers: float<->half edge cases; a 2-layer (default + "mie") 37x21 EXR round trip with exact half bits;
 * `exrheader` accepting the file and reporting ZIP compression; the EXR reader on files written directly
 * with OpenEXRCore (FLOAT and HALF channels, NONE/RLE/ZIPS/ZIP/PIZ, no A channel, offset data window);
 * PNG round trip (with and without sRGB chunk); atomic-write failure behaviour (missing directory, a
 * regular file used as directory, a write failing half-way through via RLIMIT_FSIZE) leaving neither the
 * target nor a temp file and keeping an existing target intact; io_check_writable; reader errors;
 * argument validation.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/atomic_file.h"
#include "io/exr_read.h"
#include "io/exr_write.h"
#include "io/half_float.h"
#include "io/png_io.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openexr.h>
#include "check.h"

static char g_dir[256]; /* scratch directory */

static uint32_t g_rng = 0x12345678u;
static uint32_t rng(void)
{
    g_rng ^= g_rng << 13;
    g_rng ^= g_rng >> 17;
    g_rng ^= g_rng << 5;
    return g_rng;
}

static int file_exists(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0;
}

/* Number of entries in `dir` whose name contains ".tmp." */
static int count_temp_files(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strstr(e->d_name, ".tmp.")) {
            fprintf(stderr, "  leftover temp file: %s/%s\n", dir, e->d_name);
            ++n;
        }
    }
    closedir(d);
    return n;
}

static int one_line(const char *s) { return s[0] != '\0' && strchr(s, '\n') == NULL && strchr(s, '\r') == NULL; }

static uint32_t f2u(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float u2f(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* ------------------------------------------------------------------------------------------------ */

static void test_half(void)
{
    struct {
        float f;
        uint16_t h;
    } cases[] = {
        {0.0f, 0x0000},
        {-0.0f, 0x8000},
        {1.0f, 0x3c00},
        {-2.0f, 0xc000},
        {0.5f, 0x3800},
        {65504.0f, 0x7bff},
        {-65504.0f, 0xfbff},
        {65519.0f, 0x7bff},    /* would round to 65504 anyway */
        {65520.0f, 0x7bff},    /* would round to inf under plain RNE: clamped */
        {-65520.0f, 0xfbff},
        {1e6f, 0x7bff},
        {3.4e38f, 0x7bff},
        {6.103515625e-05f, 0x0400},      /* smallest normal 2^-14 */
        {6.097555160522461e-05f, 0x03ff}, /* largest denormal */
        {5.960464477539063e-08f, 0x0001}, /* smallest denormal 2^-24 */
        {-5.960464477539063e-08f, 0x8001},
        {2.98023223876953125e-08f, 0x0000}, /* 2^-25: tie -> even (0) */
        {-2.98023223876953125e-08f, 0x8000},
        {2.9802326e-08f, 0x0001},           /* just above 2^-25 -> 1 */
        {8.940696716308594e-08f, 0x0002},   /* 1.5 * 2^-24: tie -> even (2) */
        {1.4901161193847656e-07f, 0x0002},  /* 2.5 * 2^-24: tie -> even (2) */
        {1e-10f, 0x0000},
        {1.0e-45f, 0x0000},                 /* float denormal */
        {0x1.002p0f, 0x3c00},               /* 1 + 2^-11: tie -> even (1.0) */
        {0x1.006p0f, 0x3c02},               /* 1 + 3*2^-11: tie -> even (1 + 2^-9) */
        {0x1.002002p0f, 0x3c01},            /* just above the tie */
        {0x1.001ffep0f, 0x3c00},            /* just below the tie */
        {2047.0f, 0x67ff},
        {2047.5f, 0x6800},                  /* tie between 2047 (odd) and 2048 (even) */
        {2049.0f, 0x6800},                  /* tie between 2048 (even) and 2050 */
        {2051.0f, 0x6802},                  /* tie between 2050 (odd) and 2052 (even) */
        {1e-4f, 0x068e},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        uint16_t h = io_float_to_half(cases[i].f);
        CHECK(h == cases[i].h, "float_to_half(%.9g) = 0x%04x, want 0x%04x", (double)cases[i].f, h, cases[i].h);
    }
    /* Infinities stay infinite. */
    CHECK(io_float_to_half(INFINITY) == 0x7c00, "inf -> 0x%04x", io_float_to_half(INFINITY));
    CHECK(io_float_to_half(-INFINITY) == 0xfc00, "-inf -> 0x%04x", io_float_to_half(-INFINITY));
    /* NaN stays NaN (including a NaN whose payload lives only in the low bits). */
    uint16_t hn = io_float_to_half(NAN);
    CHECK((hn & 0x7c00) == 0x7c00 && (hn & 0x3ff) != 0, "NaN -> 0x%04x", hn);
    uint16_t hn2 = io_float_to_half(u2f(0x7f800001u));
    CHECK((hn2 & 0x7c00) == 0x7c00 && (hn2 & 0x3ff) != 0, "low-payload NaN -> 0x%04x", hn2);
    uint16_t hn3 = io_float_to_half(u2f(0xffc00000u));
    CHECK((hn3 & 0xfc00) == 0xfc00 && (hn3 & 0x3ff) != 0, "-NaN -> 0x%04x", hn3);
    CHECK(isnan(io_half_to_float(0x7e00)), "half NaN -> float not NaN");
    CHECK(isnan(io_half_to_float(0x7c01)), "half sNaN -> float not NaN");
    CHECK(isinf(io_half_to_float(0x7c00)) && io_half_to_float(0x7c00) > 0, "half inf");
    CHECK(f2u(io_half_to_float(0x8000)) == 0x80000000u, "half -0 -> 0x%08x", f2u(io_half_to_float(0x8000)));
    CHECK(io_half_to_float(0x0001) == 5.960464477539063e-08f, "half 0x0001 -> %g", (double)io_half_to_float(1));
    CHECK(io_half_to_float(0x03ff) == 6.097555160522461e-05f, "half 0x03ff");
    CHECK(io_half_to_float(0x7bff) == 65504.0f, "half 0x7bff");

    /* Every non-NaN half survives half -> float -> half exactly. */
    int bad = 0;
    for (uint32_t h = 0; h < 0x10000u; ++h) {
        if ((h & 0x7c00) == 0x7c00 && (h & 0x3ff)) {
            if (!isnan(io_half_to_float((uint16_t)h))) ++bad;
            continue;
        }
        if (io_float_to_half(io_half_to_float((uint16_t)h)) != h) ++bad;
    }
    CHECK(bad == 0, "%d halfs do not round trip", bad);

    /* Round to nearest even against a brute-force reference on random floats in the finite half range. */
    bad = 0;
    for (int i = 0; i < 200000; ++i) {
        uint32_t u = rng();
        float f = u2f(u);
        if (isnan(f) || fabsf(f) > 65504.0f) continue;
        uint16_t h = io_float_to_half(f);
        double hv = (double)io_half_to_float(h);
        /* No representable half may be strictly closer; ties must pick an even mantissa. */
        uint16_t hs = h & 0x7fff;
        double err = fabs(hv - (double)f);
        for (int d = -1; d <= 1; d += 2) {
            int nb = (int)hs + d;
            if (nb < 0 || nb > 0x7bff) continue;
            double nv = (double)io_half_to_float((uint16_t)nb) * (f < 0 ? -1.0 : 1.0);
            double nerr = fabs(nv - (double)f);
            if (nerr < err || (nerr == err && (h & 1))) ++bad;
        }
    }
    CHECK(bad == 0, "%d random floats not rounded to nearest even", bad);
}

/* ------------------------------------------------------------------------------------------------ */

static int run_capture(const char *cmd, char *out, size_t out_size)
{
    FILE *p = popen(cmd, "r");
    if (!p) return -1;
    size_t n = fread(out, 1, out_size - 1, p);
    out[n] = '\0';
    return pclose(p);
}

/* Independent check of a file we wrote: `exrmaketiled` decodes it with the OpenEXR C++ library and re-encodes it
   tiled (16x8 tiles, `comp` compression); our reader must then see exactly the original half values. */
static void check_via_exrmaketiled(const char *path, const char *comp, int w, int h, const char *const *names,
                                   const uint16_t *const *src, int nlayers)
{
    char tiled[600], cmd[1400], out[4096];
    snprintf(tiled, sizeof tiled, "%s.tiled.exr", path);
    snprintf(cmd, sizeof cmd, "exrmaketiled -t 16 8 -z %s '%s' '%s' 2>&1", comp, path, tiled);
    int st = run_capture(cmd, out, sizeof out);
    CHECK(st == 0, "exrmaketiled failed (%d): %s", st, out);
    if (st != 0) return;
    for (int l = 0; l < nlayers; ++l) {
        int rw = 0, rh = 0;
        float *px = NULL;
        char err[512];
        int rc = io_read_exr(tiled, names[l], &rw, &rh, &px, err, sizeof err);
        CHECK(rc == 0 && rw == w && rh == h, "read tiled copy of %s layer '%s': %s", path, names[l], err);
        if (rc == 0) {
            size_t bad = 0, n = (size_t)w * h * 4u;
            for (size_t i = 0; i < n; ++i) bad += io_float_to_half(px[i]) != src[l][i];
            CHECK(bad == 0, "%s layer '%s' via C++ library (%s tiles): %zu values differ", path, names[l], comp, bad);
        }
        free(px);
    }
    unlink(tiled);
}

static void fill_half_layer(uint16_t *px, int w, int h, int variant)
{
    static const float specials[] = {0.0f, 1e-4f, 1.0f, 65504.0f, -0.0f, -65504.0f, 0.5f, 6.0e-8f, 3.14159f};
    size_t n = (size_t)w * (size_t)h * 4u;
    for (size_t i = 0; i < n; ++i) {
        uint16_t v;
        if (i < sizeof specials / sizeof specials[0] * 4u)
            v = io_float_to_half(specials[(i / 4u + (size_t)variant) % (sizeof specials / sizeof specials[0])]);
        else {
            do {
                v = (uint16_t)rng();
            } while ((v & 0x7c00) == 0x7c00); /* any finite half bit pattern, denormals included */
        }
        px[i] = v;
    }
}

static void test_exr_roundtrip(void)
{
    const int w = 37, h = 21;
    size_t n = (size_t)w * h * 4u;
    uint16_t *sky = malloc(n * sizeof(uint16_t));
    uint16_t *mie = malloc(n * sizeof(uint16_t));
    if (!sky || !mie) {
        CHECK(0, "out of memory");
        free(sky);
        free(mie);
        return;
    }
    fill_half_layer(sky, w, h, 0);
    fill_half_layer(mie, w, h, 3);
    /* Explicit values at known spots: pixel 0 = (0, 1e-4, 1, 65504). */
    sky[0] = io_float_to_half(0.0f);
    sky[1] = io_float_to_half(1e-4f);
    sky[2] = io_float_to_half(1.0f);
    sky[3] = io_float_to_half(65504.0f);
    mie[n - 4] = io_float_to_half(65504.0f);
    mie[n - 3] = io_float_to_half(1.0f);
    mie[n - 2] = io_float_to_half(1e-4f);
    mie[n - 1] = io_float_to_half(0.0f);

    char path[512], err[512];
    snprintf(path, sizeof path, "%s/sky.exr", g_dir);
    io_exr_layer layers[2] = {{"", sky}, {"mie", mie}};
    err[0] = '\0';
    int rc = io_write_exr(path, w, h, layers, 2, err, sizeof err);
    CHECK(rc == 0, "io_write_exr: %s", err);
    CHECK(count_temp_files(g_dir) == 0, "temp file left after successful EXR write");

    const char *names[2] = {"", "mie"};
    const uint16_t *src[2] = {sky, mie};
    for (int l = 0; l < 2; ++l) {
        int rw = 0, rh = 0;
        float *px = NULL;
        rc = io_read_exr(path, names[l], &rw, &rh, &px, err, sizeof err);
        CHECK(rc == 0, "io_read_exr('%s'): %s", names[l], err);
        if (rc != 0) continue;
        CHECK(rw == w && rh == h, "size %dx%d", rw, rh);
        size_t bad = 0, first = (size_t)-1;
        for (size_t i = 0; i < n; ++i) {
            if (io_float_to_half(px[i]) != src[l][i] || f2u(px[i]) != f2u(io_half_to_float(src[l][i]))) {
                if (first == (size_t)-1) first = i;
                ++bad;
            }
        }
        CHECK(bad == 0, "layer '%s': %zu values differ (first at %zu: got 0x%04x want 0x%04x)", names[l], bad, first,
              bad ? io_float_to_half(px[first]) : 0, bad ? src[l][first] : 0);
        free(px);
    }

    /* Missing layer: error naming the layer. */
    int rw, rh;
    float *px = (float *)&rw; /* must be reset to NULL */
    rc = io_read_exr(path, "rayleigh", &rw, &rh, &px, err, sizeof err);
    CHECK(rc == -1 && px == NULL && strstr(err, "rayleigh") && one_line(err), "missing layer: rc=%d err=%s", rc, err);

    /* exrheader accepts the file and reports ZIP compression and our channels. */
    char cmd[700], out[16384];
    snprintf(cmd, sizeof cmd, "exrheader '%s' 2>&1", path);
    int st = run_capture(cmd, out, sizeof out);
    CHECK(st == 0, "exrheader exit status %d, output:\n%s", st, out);
    CHECK(strstr(out, "compression (type compression): zip") != NULL, "exrheader does not show zip:\n%s", out);
    CHECK(strstr(out, "mie.R, 16-bit floating-point") && strstr(out, "mie.A, 16-bit floating-point") &&
              strstr(out, " R, 16-bit floating-point") && strstr(out, " A, 16-bit floating-point"),
          "exrheader channel list unexpected:\n%s", out);
    CHECK(strstr(out, "dataWindow (type box2i): (0 0) - (36 20)") != NULL, "exrheader data window:\n%s", out);
    CHECK(strstr(out, "scanlineimage") != NULL, "exrheader: not scanline:\n%s", out);

    check_via_exrmaketiled(path, "zip", w, h, names, src, 2);
    check_via_exrmaketiled(path, "piz", w, h, names, src, 2);

    /* Overwrite in place (rename over an existing file) with a single non-default layer. */
    io_exr_layer only_mie[1] = {{"mie", sky}};
    rc = io_write_exr(path, w, h, only_mie, 1, err, sizeof err);
    CHECK(rc == 0, "overwrite: %s", err);
    px = NULL;
    rc = io_read_exr(path, "mie", &rw, &rh, &px, err, sizeof err);
    CHECK(rc == 0 && px && io_float_to_half(px[3]) == sky[3] && io_float_to_half(px[n - 1]) == sky[n - 1],
          "overwrite read back: %s", err);
    free(px);
    px = NULL;
    rc = io_read_exr(path, "", &rw, &rh, &px, err, sizeof err);
    CHECK(rc == -1 && px == NULL && one_line(err), "default layer should be missing now: %s", err);

    /* 1x1 and a tall image spanning many 16-line ZIP chunks. */
    int sizes[3][2] = {{1, 1}, {3, 100}, {129, 17}};
    for (int s = 0; s < 3; ++s) {
        int sw = sizes[s][0], sh = sizes[s][1];
        size_t sn = (size_t)sw * sh * 4u;
        uint16_t *buf = malloc(sn * sizeof(uint16_t));
        if (!buf) continue;
        fill_half_layer(buf, sw, sh, s);
        io_exr_layer one[1] = {{"", buf}};
        char p2[512];
        snprintf(p2, sizeof p2, "%s/size%d.exr", g_dir, s);
        rc = io_write_exr(p2, sw, sh, one, 1, err, sizeof err);
        CHECK(rc == 0, "write %dx%d: %s", sw, sh, err);
        {
            const char *nm[1] = {""};
            const uint16_t *sp[1] = {buf};
            check_via_exrmaketiled(p2, "none", sw, sh, nm, sp, 1);
        }
        px = NULL;
        rc = io_read_exr(p2, "", &rw, &rh, &px, err, sizeof err);
        CHECK(rc == 0 && rw == sw && rh == sh, "read %dx%d: %s", sw, sh, err);
        if (rc == 0) {
            size_t bad = 0;
            for (size_t i = 0; i < sn; ++i) bad += io_float_to_half(px[i]) != buf[i];
            CHECK(bad == 0, "%dx%d: %zu values differ", sw, sh, bad);
        }
        free(px);
        free(buf);
        unlink(p2);
    }

    /* Regression: OpenEXRCore 3.1.5 stores a ZIP chunk whose compressed size equals the raw size (here 48 bytes)
       as if it were compressed, which every reader then takes for raw data. This 3x2 single-layer image hits it. */
    {
        uint16_t tiny[3 * 2 * 4];
        for (int i = 0; i < 6; ++i)
            for (int c = 0; c < 4; ++c) tiny[4 * i + c] = io_float_to_half((float)(i * 10 + c + 1));
        io_exr_layer one[1] = {{"", tiny}};
        char p3[512];
        snprintf(p3, sizeof p3, "%s/tiny.exr", g_dir);
        rc = io_write_exr(p3, 3, 2, one, 1, err, sizeof err);
        CHECK(rc == 0, "write tiny: %s", err);
        px = NULL;
        rc = io_read_exr(p3, "", &rw, &rh, &px, err, sizeof err);
        CHECK(rc == 0 && rw == 3 && rh == 2, "read tiny: %s", err);
        if (rc == 0) {
            size_t bad = 0;
            for (size_t i = 0; i < 24; ++i) bad += io_float_to_half(px[i]) != tiny[i];
            CHECK(bad == 0, "tiny (equal-size ZIP chunk): %zu values differ", bad);
        }
        free(px);
        const char *nm[1] = {""};
        const uint16_t *sp[1] = {tiny};
        check_via_exrmaketiled(p3, "zip", 3, 2, nm, sp, 1);
        unlink(p3);
    }

    /* A layer name long enough to need the long-names flag (> 31 byte channel names). */
    {
        char longname[64];
        memset(longname, 'q', 40);
        longname[40] = '\0';
        uint16_t lp[5 * 3 * 4];
        fill_half_layer(lp, 5, 3, 1);
        io_exr_layer ll[2] = {{"", lp}, {longname, lp}};
        char p5[512];
        snprintf(p5, sizeof p5, "%s/longname.exr", g_dir);
        rc = io_write_exr(p5, 5, 3, ll, 2, err, sizeof err);
        CHECK(rc == 0, "long layer name: %s", err);
        const char *nm[2] = {"", longname};
        const uint16_t *sp[2] = {lp, lp};
        if (rc == 0) check_via_exrmaketiled(p5, "zip", 5, 3, nm, sp, 2);
        unlink(p5);
    }

    /* Sweep of small single- and two-layer images with mixed compressible/incompressible content. */
    {
        int bad_files = 0;
        for (int it = 0; it < 300; ++it) {
            int sw = 1 + (int)(rng() % 9), sh = 1 + (int)(rng() % 20), nl = 1 + (int)(rng() % 2);
            size_t sn = (size_t)sw * sh * 4u;
            uint16_t *a = malloc(sn * sizeof(uint16_t)), *b = malloc(sn * sizeof(uint16_t));
            if (!a || !b) {
                free(a);
                free(b);
                break;
            }
            int mode = it % 3;
            for (size_t i = 0; i < sn; ++i) {
                uint16_t v = mode == 0 ? (uint16_t)(rng() & 0x7bff)
                                       : mode == 1 ? io_float_to_half((float)(i % 7)) : (uint16_t)(0x3c00 + (rng() & 0xf));
                a[i] = v;
                b[i] = (uint16_t)(v ^ 0x8000);
            }
            io_exr_layer ls[2] = {{"", a}, {"mie", b}};
            err[0] = '\0';
            char p4[512];
            snprintf(p4, sizeof p4, "%s/sweep.exr", g_dir);
            int ok = io_write_exr(p4, sw, sh, ls, nl, err, sizeof err) == 0;
            for (int l = 0; ok && l < nl; ++l) {
                px = NULL;
                ok = io_read_exr(p4, l ? "mie" : "", &rw, &rh, &px, err, sizeof err) == 0 && rw == sw && rh == sh;
                for (size_t i = 0; ok && i < sn; ++i) ok = io_float_to_half(px[i]) == (l ? b : a)[i];
                free(px);
            }
            if (!ok) {
                if (bad_files == 0) fprintf(stderr, "  sweep failure at %dx%d, %d layers: %s\n", sw, sh, nl, err[0] ? err : "values differ");
                ++bad_files;
            }
            unlink(p4);
            free(a);
            free(b);
        }
        CHECK(bad_files == 0, "%d of 300 small EXRs did not round trip", bad_files);
    }

    unlink(path);
    free(sky);
    free(mie);
}

/* ------------------------------------------------------------------------------------------------ */

/* Writes an EXR directly with OpenEXRCore: channels B, G, R (no A) of `type`, `comp` compression, data
   window origin (ox, oy). Planar source buffers. Returns 0 on success. */
static int write_exr_core(const char *path, int w, int h, int ox, int oy, exr_pixel_type_t type,
                          exr_compression_t comp, const float *r, const float *g, const float *b)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    int part = 0;
    if (exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS) return -1;
    exr_attr_box2i_t dw;
    exr_attr_v2f_t swc;
    memset(&dw, 0, sizeof dw);
    memset(&swc, 0, sizeof swc);
    dw.min.x = ox;
    dw.min.y = oy;
    dw.max.x = ox + w - 1;
    dw.max.y = oy + h - 1;
    int ok = exr_add_part(ctxt, "", EXR_STORAGE_SCANLINE, &part) == EXR_ERR_SUCCESS &&
             exr_initialize_required_attr(ctxt, part, &dw, &dw, 1.0f, &swc, 1.0f, EXR_LINEORDER_INCREASING_Y, comp) ==
                 EXR_ERR_SUCCESS &&
             exr_add_channel(ctxt, part, "B", type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1) == EXR_ERR_SUCCESS &&
             exr_add_channel(ctxt, part, "G", type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1) == EXR_ERR_SUCCESS &&
             exr_add_channel(ctxt, part, "R", type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1) == EXR_ERR_SUCCESS &&
             exr_write_header(ctxt) == EXR_ERR_SUCCESS;
    int32_t lpc = 0;
    ok = ok && exr_get_scanlines_per_chunk(ctxt, part, &lpc) == EXR_ERR_SUCCESS && lpc > 0;
    /* HALF sources are converted to half bits first. */
    uint16_t *hb[3] = {NULL, NULL, NULL};
    const float *fsrc[3] = {r, g, b};
    if (ok && type == EXR_PIXEL_HALF) {
        for (int c = 0; c < 3; ++c) {
            hb[c] = malloc((size_t)w * h * sizeof(uint16_t));
            if (!hb[c]) ok = 0;
            else
                for (size_t i = 0; i < (size_t)w * h; ++i) hb[c][i] = io_float_to_half(fsrc[c][i]);
        }
    }
    for (int y = oy; ok && y < oy + h; y += lpc) {
        exr_chunk_info_t ci;
        exr_encode_pipeline_t enc;
        memset(&enc, 0, sizeof enc);
        ok = exr_write_scanline_chunk_info(ctxt, part, y, &ci) == EXR_ERR_SUCCESS &&
             exr_encoding_initialize(ctxt, part, &ci, &enc) == EXR_ERR_SUCCESS;
        if (!ok) break;
        for (int c = 0; c < enc.channel_count; ++c) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            int k = ch->channel_name[0] == 'R' ? 0 : ch->channel_name[0] == 'G' ? 1 : 2;
            size_t off = (size_t)(ci.start_y - oy) * (size_t)w;
            int bpe = type == EXR_PIXEL_HALF ? 2 : 4;
            ch->user_pixel_stride = bpe;
            ch->user_line_stride = w * bpe;
            ch->user_data_type = (uint16_t)type;
            ch->user_bytes_per_element = (int16_t)bpe;
            ch->encode_from_ptr =
                type == EXR_PIXEL_HALF ? (const uint8_t *)(hb[k] + off) : (const uint8_t *)(fsrc[k] + off);
        }
        ok = exr_encoding_choose_default_routines(ctxt, part, &enc) == EXR_ERR_SUCCESS &&
             exr_encoding_run(ctxt, part, &enc) == EXR_ERR_SUCCESS;
        exr_encoding_destroy(ctxt, &enc);
    }
    for (int c = 0; c < 3; ++c) free(hb[c]);
    if (exr_finish(&ctxt) != EXR_ERR_SUCCESS) ok = 0;
    return ok ? 0 : -1;
}

static void test_exr_reader_variants(void)
{
    const int w = 19, h = 35;
    size_t n = (size_t)w * h;
    float *ch[3];
    for (int c = 0; c < 3; ++c) {
        ch[c] = malloc(n * sizeof(float));
        if (!ch[c]) {
            CHECK(0, "oom");
            return;
        }
        for (size_t i = 0; i < n; ++i) {
            /* Values exactly representable as half, so both HALF and FLOAT files compare exactly. */
            uint16_t hv;
            do {
                hv = (uint16_t)rng();
            } while ((hv & 0x7c00) == 0x7c00);
            ch[c][i] = io_half_to_float(hv);
        }
    }
    ch[0][0] = 0.0f;
    ch[1][0] = 1e-4f; /* not a half value: exact only for FLOAT files */
    ch[2][0] = 65504.0f;
    const exr_compression_t comps[] = {EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS,
                                       EXR_COMPRESSION_ZIP, EXR_COMPRESSION_PIZ};
    const char *comp_names[] = {"none", "rle", "zips", "zip", "piz"};
    const exr_pixel_type_t types[] = {EXR_PIXEL_FLOAT, EXR_PIXEL_HALF};
    for (int t = 0; t < 2; ++t) {
        for (size_t ci = 0; ci < sizeof comps / sizeof comps[0]; ++ci) {
            char path[512], err[512];
            snprintf(path, sizeof path, "%s/core_%s_%s.exr", g_dir, t == 0 ? "float" : "half", comp_names[ci]);
            int rc = write_exr_core(path, w, h, -3, 5, types[t], comps[ci], ch[0], ch[1], ch[2]);
            CHECK(rc == 0, "OpenEXRCore test writer failed for %s", path);
            if (rc != 0) continue;
            int rw = 0, rh = 0;
            float *px = NULL;
            rc = io_read_exr(path, "", &rw, &rh, &px, err, sizeof err);
            CHECK(rc == 0 && rw == w && rh == h, "read %s: %s", path, err);
            if (rc == 0) {
                size_t bad = 0;
                for (size_t i = 0; i < n; ++i) {
                    for (int c = 0; c < 3; ++c) {
                        float want = t == 0 ? ch[c][i] : io_half_to_float(io_float_to_half(ch[c][i]));
                        bad += f2u(px[4 * i + c]) != f2u(want);
                    }
                    bad += px[4 * i + 3] != 1.0f; /* missing A reads as 1 */
                }
                CHECK(bad == 0, "%s: %zu values differ", path, bad);
            }
            free(px);
            unlink(path);
        }
    }
    for (int c = 0; c < 3; ++c) free(ch[c]);
}

/* ------------------------------------------------------------------------------------------------ */

static int file_contains(const char *path, const char *needle, size_t needle_len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    static unsigned char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    for (size_t i = 0; i + needle_len <= n; ++i)
        if (memcmp(buf + i, needle, needle_len) == 0) return 1;
    return 0;
}

static void test_png_roundtrip(void)
{
    const int w = 37, h = 21;
    size_t n = (size_t)w * h * 4u;
    uint8_t *px = malloc(n);
    if (!px) {
        CHECK(0, "oom");
        return;
    }
    for (size_t i = 0; i < n; ++i) px[i] = (uint8_t)rng();
    px[0] = 0;
    px[1] = 255;
    px[2] = 128;
    px[3] = 0; /* fully transparent pixel keeps its colour */
    for (int srgb = 0; srgb <= 1; ++srgb) {
        char path[512], err[512];
        snprintf(path, sizeof path, "%s/img%d.png", g_dir, srgb);
        int rc = io_write_png(path, w, h, px, srgb, err, sizeof err);
        CHECK(rc == 0, "io_write_png: %s", err);
        CHECK(count_temp_files(g_dir) == 0, "temp file left after PNG write");
        CHECK(file_contains(path, "sRGB", 4) == srgb, "sRGB chunk presence != %d", srgb);
        CHECK(file_contains(path, "gAMA", 4) == srgb, "gAMA chunk presence != %d", srgb);
        int rw = 0, rh = 0;
        uint8_t *back = NULL;
        rc = io_read_png(path, &rw, &rh, &back, err, sizeof err);
        CHECK(rc == 0 && rw == w && rh == h, "io_read_png: %s", err);
        if (rc == 0) CHECK(memcmp(back, px, n) == 0, "PNG pixels differ");
        free(back);
        unlink(path);
    }
    free(px);
}

/* ------------------------------------------------------------------------------------------------ */

static void check_write_fails(const char *path, const char *parent_to_scan, const char *expect_reason)
{
    uint16_t half_px[4 * 4] = {0};
    uint8_t png_px[4 * 4] = {0};
    io_exr_layer layer = {"", half_px};
    char err[512];

    err[0] = '\0';
    int rc = io_write_exr(path, 2, 2, &layer, 1, err, sizeof err);
    CHECK(rc == -1, "io_write_exr into '%s' should fail", path);
    CHECK(one_line(err) && strstr(err, path) && (!expect_reason || strstr(err, expect_reason)), "exr error message: '%s'", err);
    CHECK(!file_exists(path), "'%s' exists after failed EXR write", path);

    err[0] = '\0';
    rc = io_write_png(path, 2, 2, png_px, 1, err, sizeof err);
    CHECK(rc == -1, "io_write_png into '%s' should fail", path);
    CHECK(one_line(err) && strstr(err, path) && (!expect_reason || strstr(err, expect_reason)), "png error message: '%s'", err);
    CHECK(!file_exists(path), "'%s' exists after failed PNG write", path);

    err[0] = '\0';
    rc = io_check_writable(path, err, sizeof err);
    CHECK(rc == -1, "io_check_writable('%s') should fail", path);
    CHECK(one_line(err) && strstr(err, path) && (!expect_reason || strstr(err, expect_reason)), "check_writable message: '%s'", err);

    CHECK(count_temp_files(parent_to_scan) == 0, "temp files left in %s", parent_to_scan);
}

static void test_write_errors(void)
{
    char path[600], regular[300], err[700];

    /* 1. Missing directory. */
    snprintf(path, sizeof path, "%s/missing_dir/x.exr", g_dir);
    check_write_fails(path, g_dir, strerror(ENOENT));

    /* 2. A regular file used as the directory (root ignores chmod, so this stands in for "not writable"). */
    snprintf(regular, sizeof regular, "%s/regular_file", g_dir);
    FILE *f = fopen(regular, "w");
    CHECK(f != NULL, "cannot create %s", regular);
    if (f) fclose(f);
    snprintf(path, sizeof path, "%s/x.exr", regular);
    check_write_fails(path, g_dir, strerror(ENOTDIR));
    unlink(regular);

    /* 2b. A directory where even root cannot create files (procfs), and, when not root, a read-only directory. */
    if (access("/proc/self", F_OK) == 0) check_write_fails("/proc/vksky_test_io.exr", "/proc", NULL);
    if (geteuid() != 0) {
        char rodir[300];
        snprintf(rodir, sizeof rodir, "%s/readonly", g_dir);
        if (mkdir(rodir, 0555) == 0) {
            snprintf(path, sizeof path, "%s/x.exr", rodir);
            check_write_fails(path, rodir, strerror(EACCES));
            rmdir(rodir);
        }
    }

    /* 3. Writable directory: io_check_writable succeeds; a directory as target fails. */
    snprintf(path, sizeof path, "%s/ok.exr", g_dir);
    CHECK(io_check_writable(path, err, sizeof err) == 0, "io_check_writable('%s'): %s", path, err);
    char cwd[1024];
    if (getcwd(cwd, sizeof cwd) && chdir(g_dir) == 0) {
        CHECK(io_check_writable("relative_name.exr", err, sizeof err) == 0, "relative path: %s", err);
        uint8_t px4[4] = {1, 2, 3, 4};
        CHECK(io_write_png("relative_name.png", 1, 1, px4, 0, err, sizeof err) == 0, "relative write: %s", err);
        CHECK(file_exists("relative_name.png") && count_temp_files(".") == 0, "relative write result");
        unlink("relative_name.png");
        CHECK(chdir(cwd) == 0, "chdir back");
    }
    CHECK(io_check_writable(g_dir, err, sizeof err) == -1 && one_line(err), "directory as target: %s", err);
    snprintf(path, sizeof path, "%s/", g_dir);
    CHECK(io_check_writable(path, err, sizeof err) == -1 && one_line(err), "trailing slash: %s", err);

    /* 4. Failure half-way through the write (file size limit): no temp left, existing target intact. */
    const int w = 256, h = 256;
    uint16_t *noise = malloc((size_t)w * h * 4u * sizeof(uint16_t));
    uint8_t *noise8 = malloc((size_t)w * h * 4u);
    if (!noise || !noise8) {
        CHECK(0, "oom");
        free(noise);
        free(noise8);
        return;
    }
    for (size_t i = 0; i < (size_t)w * h * 4u; ++i) {
        noise[i] = (uint16_t)(rng() & 0x3bff);
        noise8[i] = (uint8_t)rng();
    }
    const char *exts[2] = {"exr", "png"};
    for (int k = 0; k < 2; ++k) {
        snprintf(path, sizeof path, "%s/existing.%s", g_dir, exts[k]);
        f = fopen(path, "w");
        if (f) {
            fputs("previous contents", f);
            fclose(f);
        }
        struct rlimit old;
        getrlimit(RLIMIT_FSIZE, &old);
        struct rlimit lim = old;
        lim.rlim_cur = 4096;
        void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
        int lim_ok = setrlimit(RLIMIT_FSIZE, &lim) == 0;
        CHECK(lim_ok, "setrlimit failed: %s", strerror(errno));
        int rc;
        err[0] = '\0';
        if (k == 0) {
            io_exr_layer l = {"", noise};
            rc = io_write_exr(path, w, h, &l, 1, err, sizeof err);
        } else {
            rc = io_write_png(path, w, h, noise8, 0, err, sizeof err);
        }
        setrlimit(RLIMIT_FSIZE, &old);
        signal(SIGXFSZ, prev);
        if (lim_ok) {
            CHECK(rc == -1, "%s write should fail past RLIMIT_FSIZE", exts[k]);
            CHECK(one_line(err) && strstr(err, path) && strstr(err, strerror(EFBIG)), "%s message: '%s'", exts[k],
                  err);
            CHECK(file_contains(path, "previous contents", 17), "existing %s target was modified", exts[k]);
            CHECK(count_temp_files(g_dir) == 0, "temp file left after failed %s write", exts[k]);
        }
        unlink(path);
    }
    free(noise);
    free(noise8);
}

static void test_bad_args_and_readers(void)
{
    char err[512], path[512];
    uint16_t px[4 * 4] = {0};
    uint8_t px8[4 * 4] = {0};
    io_exr_layer l = {"", px};
    io_exr_layer dup[2] = {{"a", px}, {"a", px}};
    io_exr_layer nul[1] = {{NULL, px}};
    snprintf(path, sizeof path, "%s/bad.exr", g_dir);

    CHECK(io_write_exr(path, 0, 2, &l, 1, err, sizeof err) == -1 && one_line(err), "w=0: %s", err);
    CHECK(io_write_exr(path, 2, -1, &l, 1, err, sizeof err) == -1 && one_line(err), "h<0: %s", err);
    CHECK(io_write_exr(path, 2, 2, NULL, 1, err, sizeof err) == -1 && one_line(err), "NULL layers: %s", err);
    CHECK(io_write_exr(path, 2, 2, &l, 0, err, sizeof err) == -1 && one_line(err), "0 layers: %s", err);
    CHECK(io_write_exr(path, 2, 2, dup, 2, err, sizeof err) == -1 && strstr(err, "duplicate"), "dup: %s", err);
    CHECK(io_write_exr(path, 2, 2, nul, 1, err, sizeof err) == -1 && one_line(err), "NULL name: %s", err);
    CHECK(io_write_exr(NULL, 2, 2, &l, 1, err, sizeof err) == -1 && one_line(err), "NULL path: %s", err);
    CHECK(io_write_exr("", 2, 2, &l, 1, err, sizeof err) == -1 && one_line(err), "empty path: %s", err);
    CHECK(io_write_exr(path, 2, 2, &l, 1, NULL, 0) == 0, "NULL err buffer on success");
    CHECK(io_write_exr(path, 0, 2, &l, 1, NULL, 0) == -1, "NULL err buffer on failure");
    CHECK(io_write_png(path, 2, 2, NULL, 0, err, sizeof err) == -1 && one_line(err), "NULL png px: %s", err);
    CHECK(io_write_png(path, 2, 0, px8, 0, err, sizeof err) == -1 && one_line(err), "png h=0: %s", err);
    char tiny[8];
    CHECK(io_write_png(path, 2, 0, px8, 0, tiny, sizeof tiny) == -1 && strlen(tiny) < sizeof tiny, "truncated err");

    int w, h;
    float *f = NULL;
    uint8_t *b = NULL;
    char missing[512];
    snprintf(missing, sizeof missing, "%s/does_not_exist.exr", g_dir);
    CHECK(io_read_exr(missing, "", &w, &h, &f, err, sizeof err) == -1 && f == NULL && strstr(err, missing) &&
              strstr(err, strerror(ENOENT)) && one_line(err),
          "read missing exr: %s", err);
    CHECK(io_read_png(missing, &w, &h, &b, err, sizeof err) == -1 && b == NULL && strstr(err, missing) &&
              one_line(err),
          "read missing png: %s", err);
    CHECK(io_read_exr(g_dir, "", &w, &h, &f, err, sizeof err) == -1 && one_line(err), "read dir: %s", err);

    /* A PNG is not an EXR and vice versa; a truncated EXR fails cleanly. */
    char pngpath[512];
    snprintf(pngpath, sizeof pngpath, "%s/small.png", g_dir);
    CHECK(io_write_png(pngpath, 2, 2, px8, 0, err, sizeof err) == 0, "write small png: %s", err);
    CHECK(io_read_exr(pngpath, "", &w, &h, &f, err, sizeof err) == -1 && f == NULL && one_line(err) &&
              strstr(err, pngpath),
          "png as exr: %s", err);
    CHECK(io_read_png(path, &w, &h, &b, err, sizeof err) == -1 && b == NULL && one_line(err), "exr as png: %s", err);
    struct stat st;
    if (stat(path, &st) == 0) {
        CHECK(truncate(path, st.st_size / 2) == 0, "truncate");
        int rc = io_read_exr(path, "", &w, &h, &f, err, sizeof err);
        CHECK(rc == -1 && f == NULL && one_line(err), "truncated exr should fail: rc=%d %s", rc, err);
        if (rc == 0) free(f);
        f = NULL;
    }
    CHECK(truncate(pngpath, 40) == 0, "truncate png");
    CHECK(io_read_png(pngpath, &w, &h, &b, err, sizeof err) == -1 && b == NULL && one_line(err), "truncated png: %s",
          err);
    CHECK(io_read_exr(path, "", NULL, &h, &f, err, sizeof err) == -1, "NULL width");
    unlink(pngpath);
    unlink(path);
}

int main(void)
{
    snprintf(g_dir, sizeof g_dir, "/tmp/vksky_test_io_XXXXXX");
    if (!mkdtemp(g_dir)) {
        perror("mkdtemp");
        return 2;
    }
    test_half();
    test_exr_roundtrip();
    test_exr_reader_variants();
    test_png_roundtrip();
    test_write_errors();
    test_bad_args_and_readers();

    if (rmdir(g_dir) != 0) {
        fprintf(stderr, "note: scratch directory %s not empty: %s\n", g_dir, strerror(errno));
        ++check_failures;
    }
    printf("test_io: %d checks, %d failures\n", check_count, check_failures);
    return check_failures ? 1 : 0;
}
