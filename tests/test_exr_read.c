/* The EXR input side (src/io/exr_read*.c) against files written independently: straight through OpenEXRCore's
 * encoder (tests/exr_core_writer.h: HALF/FLOAT/UINT, scanline/tiled, single/multi-part, every compression the C
 * library encodes, offset data windows, worldToCamera/worldToNDC) and, where installed, by OpenImageIO's oiiotool
 * (the C++ OpenEXR library: DWAA/DWAB, and the reference decode of the lossy B44/B44A files). Values read back are
 * compared with the values the writer stored, decoded here by the format's definition: exact for lossless codecs,
 * PXR24's 24-bit float within its rounding, B44 against the C++ library's decode. Then every class of bad file gives
 * a nonzero return and one line naming the file and the problem. Exit 0 = pass.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "io/exr_layers.h"
#include "io/exr_read.h"

#include "exr_core_writer.h"

#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "check.h"
static int g_skipped = 0;   /* sections left out for a missing tool: the run exits 77 (ctest SKIP), issue 31 */

static char g_dir[128];
static const char *comp_name[] = {"NONE", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};

static const char *tmp_path(const char *name)
{
    static char buf[8][256];
    static int i = 0;
    i = (i + 1) % 8;
    snprintf(buf[i], sizeof buf[i], "%s/%s", g_dir, name);
    return buf[i];
}

static int have_tool(const char *tool)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

/* PXR24 keeps a float's top 24 bits, rounded: the stored bit pattern moves by at most half of 2^8. */
static int pxr24_close(float got, float want)
{
    uint32_t g, w;
    memcpy(&g, &got, 4);
    memcpy(&w, &want, 4);
    return (g >> 31) == (w >> 31) && (g > w ? g - w : w - g) <= 128u; /* the low 8 bits, rounded */
}

/* Reads every channel of part `p` of the file and compares with what tw_write stored. mode: 0 exact, 1 PXR24 (floats
   within rounding, the rest exact). Returns the number of mismatches, or -1 when a read failed. */
static long compare_part(const char *path, const tw_part *P, int p, int mode, char *err, size_t err_size)
{
    const char *names[8];
    for (int c = 0; c < P->nch; ++c) names[c] = P->ch[c].name;
    float *out = (float *)malloc((size_t)P->w * P->h * P->nch * sizeof(float));
    if (!out) return -1;
    if (io_exr_read_channels(path, names, P->nch, out, err, err_size) != 0) {
        free(out);
        return -1;
    }
    long bad = 0;
    for (int y = 0; y < P->h; ++y) {
        for (int x = 0; x < P->w; ++x) {
            for (int c = 0; c < P->nch; ++c) {
                int t = P->ch[c].type;
                float want = tw_expect(tw_bits(p, c, x, y, t, P->smooth), t);
                float got = out[((size_t)y * P->w + x) * P->nch + c];
                int ok = mode == 1 && t == EXR_PIXEL_FLOAT ? pxr24_close(got, want) : memcmp(&got, &want, 4) == 0;
                if (!ok && bad++ < 3)
                    fprintf(stderr, "  %s (%d,%d) %s: got %.9g want %.9g\n", path, x, y, P->ch[c].name, got, want);
            }
        }
    }
    free(out);
    return bad;
}

/* One part with one channel of each type, offset data window, edge tiles and edge chunks. */
static tw_part mixed_part(int compression, int tiled, int w, int h)
{
    tw_part P = {.name = "main", .tiled = tiled, .tile_w = 16, .tile_h = 8, .compression = compression,
                 .x0 = -3, .y0 = 5, .w = w, .h = h, .nch = 4,
                 .ch = {{"A", EXR_PIXEL_HALF}, {"B", EXR_PIXEL_HALF}, {"Position.X", EXR_PIXEL_FLOAT},
                        {"id", EXR_PIXEL_UINT}}};
    return P;
}

static void test_codecs(void)
{
    for (int comp = 0; comp <= 5; ++comp) { /* the lossless ones, and PXR24 */
        for (int tiled = 0; tiled < 2; ++tiled) {
            char name[64];
            snprintf(name, sizeof name, "codec_%s_%d.exr", comp_name[comp], tiled);
            const char *path = tmp_path(name);
            tw_part P = mixed_part(comp, tiled, 37, 45);
            CHECK(tw_write(path, &P, 1) == 0, "write %s", path);
            char err[512] = "";
            io_exr_info info;
            CHECK(io_exr_read_info(path, &info, err, sizeof err) == 0, "%s", err);
            CHECK(info.width == 37 && info.height == 45 && info.channel_count == 4 && info.part_count == 1,
                  "%s: %dx%d, %d channels", path, info.width, info.height, info.channel_count);
            for (int i = 0; i < info.channel_count; ++i) {
                int k = 0;
                while (k < 4 && strcmp(P.ch[k].name, info.channels[i].name) != 0) ++k;
                CHECK(k < 4 && info.channels[i].pixel_type == P.ch[k].type && info.channels[i].part == 0,
                      "%s: channel '%s'", path, info.channels[i].name);
            }
            CHECK(!info.has_world_to_camera && !info.has_world_to_ndc, "%s: no matrices were written", path);
            io_exr_info_free(&info);
            long bad = compare_part(path, &P, 0, comp == 5, err, sizeof err);
            CHECK(bad == 0, "%s: %ld mismatches %s", path, bad, err);
        }
    }
}

/* B44/B44A are lossy for HALF (FLOAT and UINT are stored as they are): the C++ library's decode (oiiotool, rewritten
   uncompressed) is the reference, and the error against the stored values stays within B44's quantisation. */
static void test_b44(int have_oiio)
{
    for (int comp = 6; comp <= 7; ++comp) {
        for (int tiled = 0; tiled < 2; ++tiled) {
            char name[64], ref[64];
            snprintf(name, sizeof name, "b44_%s_%d.exr", comp_name[comp], tiled);
            snprintf(ref, sizeof ref, "b44_%s_%d_ref.exr", comp_name[comp], tiled);
            const char *path = tmp_path(name), *refpath = tmp_path(ref);
            tw_part P = mixed_part(comp, tiled, 48, 40); /* whole tiles: see test_b44_edge_tiles */
            P.smooth = 1;
            CHECK(tw_write(path, &P, 1) == 0, "write %s", path);
            const char *names[4] = {"A", "B", "Position.X", "id"};
            float *got = (float *)malloc(48 * 40 * 4 * sizeof(float));
            float *want = (float *)malloc(48 * 40 * 4 * sizeof(float));
            char err[512] = "";
            CHECK(io_exr_read_channels(path, names, 4, got, err, sizeof err) == 0, "%s", err);
            double max_rel = 0.0;
            for (int i = 0; i < 48 * 40; ++i) {
                int x = i % 48, y = i / 48;
                for (int c = 0; c < 4; ++c) {
                    float v = tw_expect(tw_bits(0, c, x, y, P.ch[c].type, 1), P.ch[c].type);
                    if (P.ch[c].type != EXR_PIXEL_HALF) {
                        CHECK(got[i * 4 + c] == v, "%s: lossless channel %s differs", path, names[c]);
                    } else {
                        double rel = fabs(got[i * 4 + c] - v) / fabs(v);
                        if (rel > max_rel) max_rel = rel;
                    }
                }
            }
            CHECK(max_rel < 0.01, "%s: B44 error %.4f on a smooth ramp", path, max_rel);
            if (have_oiio) {
                char cmd[600];
                snprintf(cmd, sizeof cmd, "oiiotool '%s' --compression none -o '%s' >/dev/null 2>&1", path, refpath);
                CHECK(system(cmd) == 0, "%s", cmd);
                CHECK(io_exr_read_channels(refpath, names, 4, want, err, sizeof err) == 0, "%s", err);
                long diff = 0;
                for (int i = 0; i < 48 * 40 * 4; ++i) {
                    if (i % 4 == 3) continue; /* oiiotool rescales UINT to [0, 1]: checked exactly above */
                    if (memcmp(&got[i], &want[i], 4) != 0 && diff++ < 4)
                        fprintf(stderr, "  %s [%d,%d] %s: %.9g vs C++ %.9g (stored %.9g)\n", path, i / 4 % 48, i / 4 / 48,
                                names[i % 4], got[i], want[i],
                                tw_expect(tw_bits(0, i % 4, i / 4 % 48, i / 4 / 48, P.ch[i % 4].type, 1), P.ch[i % 4].type));
                }
                CHECK(diff == 0, "%s: %ld values differ from the C++ library's decode", path, diff);
            }
            free(got);
            free(want);
        }
    }
}

/* OpenEXRCore 3.1.5 refuses a tiled B44 chunk whose packed size exceeds its unpacked size (an edge tile of a
   mixed-type part: B44 pads HALF data to 4x4 blocks), though the C++ library reads it. Either it reads right or
   it says why in one line; never garbage. */
static void test_b44_edge_tiles(void)
{
    const char *path = tmp_path("b44_edge.exr");
    tw_part P = mixed_part(EXR_COMPRESSION_B44, 1, 37, 21);
    P.smooth = 1;
    CHECK(tw_write(path, &P, 1) == 0, "write %s", path);
    const char *names[1] = {"id"};
    float *out = (float *)malloc(37 * 21 * sizeof(float));
    char err[512] = "";
    int r = io_exr_read_channels(path, names, 1, out, err, sizeof err);
    if (r == 0) {
        for (int i = 0; i < 37 * 21; ++i)
            CHECK(out[i] == (float)tw_bits(0, 3, i % 37, i / 37, EXR_PIXEL_UINT, 1), "pixel %d", i);
    } else {
        CHECK(strstr(err, path) == err && strstr(err, "B44") && !strchr(err, '\n'), "message: %s", err);
    }
    printf("B44 tiled with edge tiles: %s\n", r == 0 ? "read" : err);
    free(out);
}

/* DWAA/DWAB: OpenEXR 3.1's C library neither writes nor decodes them; files from the C++ library (oiiotool) must
   give the message that says so and what to do. */
static void test_dwa(int have_oiio)
{
    if (!have_oiio) {
        ++g_skipped, printf("SKIP DWAA/DWAB files: oiiotool not installed (openimageio-tools)\n");
        return;
    }
    const char *src = tmp_path("dwa_src.exr");
    tw_part P = mixed_part(EXR_COMPRESSION_NONE, 0, 64, 40);
    P.smooth = 1;
    CHECK(tw_write(src, &P, 1) == 0, "write %s", src);
    for (int i = 0; i < 2; ++i) {
        const char *path = tmp_path(i ? "dwab.exr" : "dwaa.exr");
        char cmd[600], err[512] = "";
        snprintf(cmd, sizeof cmd, "oiiotool '%s' --compression %s -o '%s' >/dev/null 2>&1", src, i ? "dwab" : "dwaa",
                 path);
        CHECK(system(cmd) == 0, "%s", cmd);
        io_exr_info info;
        CHECK(io_exr_read_info(path, &info, err, sizeof err) == 0, "the header is fine: %s", err);
        io_exr_info_free(&info);
        const char *names[1] = {"A"};
        float out[64 * 40];
        CHECK(io_exr_read_channels(path, names, 1, out, err, sizeof err) != 0, "%s decoded?", path);
        CHECK(strstr(err, i ? "DWAB" : "DWAA") && strstr(err, "cannot decode") && strstr(err, "re-save"), "%s", err);
    }
}

/* Blender's shape: a multi-part file, one part per pass, full channel names; the camera matrices in the header. */
static void test_multipart(void)
{
    const char *path = tmp_path("multipart.exr");
    tw_part parts[2] = {
        {.name = "ViewLayer.Combined", .compression = EXR_COMPRESSION_ZIP, .w = 40, .h = 24, .nch = 4,
         .ch = {{"ViewLayer.Combined.R", EXR_PIXEL_HALF}, {"ViewLayer.Combined.G", EXR_PIXEL_HALF},
                {"ViewLayer.Combined.B", EXR_PIXEL_HALF}, {"ViewLayer.Combined.A", EXR_PIXEL_HALF}},
         .has_w2c = 1},
        {.name = "ViewLayer.Position", .tiled = 1, .tile_w = 32, .tile_h = 16, .compression = EXR_COMPRESSION_PIZ,
         .x0 = 10, .y0 = -7, .w = 40, .h = 24, .nch = 3,
         .ch = {{"ViewLayer.Position.X", EXR_PIXEL_FLOAT}, {"ViewLayer.Position.Y", EXR_PIXEL_FLOAT},
                {"ViewLayer.Position.Z", EXR_PIXEL_FLOAT}},
         .has_w2n = 1}};
    for (int i = 0; i < 16; ++i) {
        parts[0].w2c[i] = (float)(i * i) - 7.25f;
        parts[1].w2n[i] = 1.0f / (float)(i + 3);
    }
    CHECK(tw_write(path, parts, 2) == 0, "write %s", path);
    char err[512] = "";
    io_exr_info info;
    CHECK(io_exr_read_info(path, &info, err, sizeof err) == 0, "%s", err);
    CHECK(info.part_count == 2 && info.channel_count == 7 && info.width == 40 && info.height == 24, "%d parts %d ch",
          info.part_count, info.channel_count);
    for (int i = 0; i < info.channel_count; ++i) {
        int p = strstr(info.channels[i].name, "Position") ? 1 : 0;
        CHECK(info.channels[i].part == p &&
                  info.channels[i].pixel_type == (p ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF),
              "%s: part %d type %d", info.channels[i].name, info.channels[i].part, info.channels[i].pixel_type);
    }
    CHECK(info.has_world_to_camera && memcmp(info.world_to_camera, parts[0].w2c, sizeof parts[0].w2c) == 0,
          "worldToCamera");
    CHECK(info.has_world_to_ndc && memcmp(info.world_to_ndc, parts[1].w2n, sizeof parts[1].w2n) == 0, "worldToNDC");
    io_exr_info_free(&info);
    CHECK(info.channels == NULL && info.channel_count == 0, "freed info is zeroed");
    io_exr_info_free(&info); /* twice is fine */

    /* Channels from both parts, interleaved in the caller's order, one asked twice. */
    const char *names[5] = {"ViewLayer.Position.Z", "ViewLayer.Combined.R", "ViewLayer.Position.X",
                            "ViewLayer.Combined.A", "ViewLayer.Position.Z"};
    const int part_of[5] = {1, 0, 1, 0, 1}, chan_of[5] = {2, 0, 0, 3, 2};
    float out[40 * 24 * 5];
    CHECK(io_exr_read_channels(path, names, 5, out, err, sizeof err) == 0, "%s", err);
    long bad = 0;
    for (int i = 0; i < 40 * 24; ++i) {
        for (int k = 0; k < 5; ++k) {
            int t = parts[part_of[k]].ch[chan_of[k]].type;
            float want = tw_expect(tw_bits(part_of[k], chan_of[k], i % 40, i / 40, t, 0), t);
            bad += memcmp(&out[i * 5 + k], &want, 4) != 0;
        }
    }
    CHECK(bad == 0, "%ld mismatches across parts", bad);

    /* A part of another size is refused when read, not when the header is listed. */
    const char *mis = tmp_path("mismatch.exr");
    parts[1].h = 23;
    CHECK(tw_write(mis, parts, 2) == 0, "write %s", mis);
    CHECK(io_exr_read_info(mis, &info, err, sizeof err) == 0, "%s", err);
    io_exr_info_free(&info);
    CHECK(io_exr_read_channels(mis, names, 2, out, err, sizeof err) != 0 && strstr(err, "mismatched part sizes") &&
              strstr(err, "40x23"),
          "%s", err);
    CHECK(io_exr_read_channels(mis, names + 1, 1, out, err, sizeof err) == 0, "part 0 alone reads: %s", err);
}

/* The C++ library's multi-part writer (exrmultipart -combine, package openexr; -override: parts share one
   display window): two single-part files, one tiled,
   become parts of one file; every value comes back. */
static void test_exrmultipart(void)
{
    if (!have_tool("exrmultipart")) {
        ++g_skipped, printf("SKIP exrmultipart files: not installed (package openexr)\n");
        return;
    }
    tw_part a = {.name = "beauty", .compression = EXR_COMPRESSION_PIZ, .w = 33, .h = 19, .nch = 2,
                 .ch = {{"Combined.R", EXR_PIXEL_HALF}, {"Combined.G", EXR_PIXEL_HALF}}};
    tw_part b = {.name = "position", .tiled = 1, .tile_w = 8, .tile_h = 8, .compression = EXR_COMPRESSION_ZIP,
                 .x0 = 4, .y0 = 9, .w = 33, .h = 19, .nch = 1, .ch = {{"Position.Z", EXR_PIXEL_FLOAT}}};
    char pa[256], pb[256], pc[256], cmd[900], err[512] = "";
    snprintf(pa, sizeof pa, "%s", tmp_path("mp_a.exr"));
    snprintf(pb, sizeof pb, "%s", tmp_path("mp_b.exr"));
    snprintf(pc, sizeof pc, "%s", tmp_path("mp_combined.exr"));
    CHECK(tw_write(pa, &a, 1) == 0 && tw_write(pb, &b, 1) == 0, "write parts");
    snprintf(cmd, sizeof cmd, "exrmultipart -combine -i '%s' '%s' -o '%s' -override 1 >/dev/null 2>&1", pa, pb, pc);
    CHECK(system(cmd) == 0, "%s", cmd);
    io_exr_info info;
    CHECK(io_exr_read_info(pc, &info, err, sizeof err) == 0 && info.part_count == 2 && info.channel_count == 3,
          "%s (%d parts)", err, info.part_count);
    io_exr_info_free(&info);
    const char *names[3] = {"Position.Z", "Combined.G", "Combined.R"};
    const int chan_of[3] = {0, 1, 0}, type[3] = {EXR_PIXEL_FLOAT, EXR_PIXEL_HALF, EXR_PIXEL_HALF};
    float out[33 * 19 * 3];
    CHECK(io_exr_read_channels(pc, names, 3, out, err, sizeof err) == 0, "%s", err);
    long bad = 0;
    for (int i = 0; i < 33 * 19; ++i) {
        for (int k = 0; k < 3; ++k) {
            /* tw_bits numbers parts by the part index at write time: both were part 0 of their own file */
            float want = tw_expect(tw_bits(0, chan_of[k], i % 33, i / 33, type[k], 0), type[k]);
            bad += memcmp(&out[i * 3 + k], &want, 4) != 0;
        }
    }
    CHECK(bad == 0, "%ld mismatches in the exrmultipart file", bad);
}

/* ---- the multilayer writer ------------------------------------------------------------------------------ */

/* fp16 of x as io_write_exr_layers documents it: round to nearest even, finite values beyond +-65504 clamp,
   inf and NaN stay. Computed from the definition (a power-of-two quantum per binade), not from any converter. */
static float half_round(float x)
{
    if (isnan(x) || isinf(x)) return x;
    if (fabsf(x) >= 65504.0f) return x < 0 ? -65504.0f : 65504.0f;
    if (x == 0.0f) return x;
    int e = (int)floor(log2(fabs((double)x)));
    if (e < -14) e = -14; /* subnormal halves share the smallest quantum, 2^-24 */
    double q = ldexp(1.0, e - 10);
    double r = nearbyint((double)x / q) * q; /* the default rounding mode: ties to even */
    if (fabs(r) > 65504.0) r = r < 0 ? -65504.0 : 65504.0;
    return (float)(r == 0.0 ? copysign(0.0, x) : r);
}

static void test_layers_roundtrip(int have_oiio)
{
    enum { W = 61, H = 37 }; /* 3 ZIP chunks of 16 lines, the last one short */
    static const char *lname[4] = {"", "sky", "transmittance", "a_layer_name_longer_than_31_bytes_needs_longnames"};
    static const int lch[4] = {4, 3, 3, 3};
    float *px[4];
    io_exr_out_layer layers[4];
    uint32_t s = 12345;
    for (int l = 0; l < 4; ++l) {
        px[l] = (float *)malloc((size_t)W * H * lch[l] * sizeof(float));
        for (int i = 0; i < W * H * lch[l]; ++i) {
            s = s * 1664525u + 1013904223u;
            float u = (float)(s >> 8) / 16777216.0f;
            switch (i % 7) {
            case 0: px[l][i] = u; break;
            case 1: px[l][i] = -u * 100.0f; break;
            case 2: px[l][i] = u * 1e-6f; break;              /* subnormal halves */
            case 3: px[l][i] = 60000.0f + u * 20000.0f; break; /* around the clamp */
            case 4: px[l][i] = (float)(s % 2048) / 64.0f; break; /* exact in half */
            case 5: px[l][i] = (s & 256) ? INFINITY : -INFINITY; break;
            default: px[l][i] = (s & 512) ? NAN : u * 3.0f; break;
            }
        }
        layers[l] = (io_exr_out_layer){lname[l], lch[l], px[l]};
    }
    const char *path = tmp_path("layers.exr");
    char err[512] = "";
    CHECK(io_write_exr_layers(path, W, H, layers, 4, err, sizeof err) == 0, "%s", err);
    io_exr_info info;
    CHECK(io_exr_read_info(path, &info, err, sizeof err) == 0, "%s", err);
    CHECK(info.width == W && info.height == H && info.part_count == 1 && info.channel_count == 13, "%dx%d %d ch",
          info.width, info.height, info.channel_count);
    for (int i = 0; i < info.channel_count; ++i)
        CHECK(info.channels[i].pixel_type == EXR_PIXEL_HALF, "%s is not HALF", info.channels[i].name);
    io_exr_info_free(&info);
    static const char comp[4] = {'R', 'G', 'B', 'A'};
    for (int l = 0; l < 4; ++l) {
        char names[4][80];
        const char *np[4];
        for (int c = 0; c < lch[l]; ++c) {
            snprintf(names[c], sizeof names[c], "%s%s%c", lname[l], lname[l][0] ? "." : "", comp[c]);
            np[c] = names[c];
        }
        float *got = (float *)malloc((size_t)W * H * lch[l] * sizeof(float));
        CHECK(io_exr_read_channels(path, np, lch[l], got, err, sizeof err) == 0, "%s", err);
        long bad = 0;
        for (int i = 0; i < W * H * lch[l]; ++i) {
            float want = half_round(px[l][i]);
            int same = isnan(want) ? isnan(got[i]) : memcmp(&want, &got[i], 4) == 0;
            if (!same && bad++ < 3)
                fprintf(stderr, "  layer '%s' value %d: wrote %.9g, read %.9g, fp16 is %.9g\n", lname[l], i, px[l][i],
                        got[i], want);
        }
        CHECK(bad == 0, "layer '%s': %ld values are not the fp16 of what was written", lname[l], bad);
        free(got);
    }
    if (have_oiio) { /* the compositing tools' view: every layer channel listed */
        char cmd[600];
        snprintf(cmd, sizeof cmd, "oiiotool --info -v '%s' 2>&1", path);
        FILE *f = popen(cmd, "r");
        char out[8192] = "";
        size_t n = f ? fread(out, 1, sizeof out - 1, f) : 0;
        out[n] = '\0';
        CHECK(f && pclose(f) == 0, "%s", cmd);
        const char *want[] = {"R", "G", "B", "A", "sky.R", "sky.G", "sky.B", "transmittance.R", "transmittance.G",
                              "transmittance.B", "a_layer_name_longer_than_31_bytes_needs_longnames.R"};
        /* "    channel list: R, G, B, A, sky.R, ..." (a type in brackets only where types differ) */
        char *list = strstr(out, "channel list:");
        CHECK(list != NULL, "oiiotool printed no channel list: %s", out);
        char listed[32][96];
        int nlisted = 0;
        if (list) {
            char *eol = strchr(list, '\n');
            if (eol) *eol = '\0';
            for (char *tok = strtok(list + strlen("channel list:"), ", "); tok && nlisted < 32; tok = strtok(NULL, ", "))
                if (tok[0] != '(') snprintf(listed[nlisted++], sizeof listed[0], "%s", tok);
        }
        CHECK(nlisted == 13, "oiiotool lists %d channels, 13 written", nlisted);
        for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
            int found = 0;
            for (int k = 0; k < nlisted; ++k) found |= strcmp(listed[k], want[i]) == 0;
            CHECK(found, "oiiotool does not list '%s'", want[i]);
        }
    } else {
        ++g_skipped, printf("SKIP oiiotool layer listing: openimageio-tools not installed\n");
    }

    /* Bad arguments: -1, one line, and no file (and no temporary) left behind. */
    const char *bad_path = tmp_path("bad_layers.exr");
    io_exr_out_layer b[2] = {{"sky", 3, px[1]}, {"sky", 3, px[2]}};
    struct {
        int w, h, n, ch;
        const char *name0, *name1;
        int null_px;
        const char *want;
    } cases[] = {
        {W, H, 2, 3, "sky", "sky", 0, "duplicate layer name 'sky'"},
        {W, H, 1, 5, "sky", "x", 0, "5 channels (3 or 4 accepted)"},
        {W, H, 1, 3, ".sky", "x", 0, "starts or ends with '.'"},
        {W, H, 1, 3, "sky.", "x", 0, "starts or ends with '.'"},
        {W, H, 1, 3, "sky", "x", 1, "has no pixels"},
        {0, H, 1, 3, "sky", "x", 0, "invalid image size"},
        {W, H, 0, 3, "sky", "x", 0, "invalid layer list"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        b[0].name = cases[i].name0, b[1].name = cases[i].name1, b[0].channels = cases[i].ch;
        b[0].pixels = cases[i].null_px ? NULL : px[1];
        err[0] = '\0';
        int r = io_write_exr_layers(bad_path, cases[i].w, cases[i].h, b, cases[i].n, err, sizeof err);
        CHECK(r == -1 && strstr(err, cases[i].want) && !strchr(err, '\n') && access(bad_path, F_OK) != 0,
              "case %zu: r=%d '%s'", i, r, err);
    }
    char nodir[300];
    snprintf(nodir, sizeof nodir, "%s/no/such/dir/x.exr", g_dir);
    CHECK(io_write_exr_layers(nodir, W, H, layers, 1, err, sizeof err) == -1 && strstr(err, "cannot write"), "%s",
          err);
    DIR *d = opendir(g_dir);
    for (struct dirent *e; d && (e = readdir(d));)
        CHECK(!strstr(e->d_name, ".tmp."), "temporary file left: %s", e->d_name);
    if (d) closedir(d);
    for (int l = 0; l < 4; ++l) free(px[l]);
}

/* ---- bad files ------------------------------------------------------------------------------------------ */

static unsigned char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = (unsigned char *)malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    *size = (size_t)n;
    return b;
}

static void spit(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        if (size) fwrite(data, 1, size, f);
        fclose(f);
    }
}

static long find_bytes(const unsigned char *b, size_t n, const void *pat, size_t m)
{
    for (size_t i = 0; i + m <= n; ++i)
        if (memcmp(b + i, pat, m) == 0) return (long)i;
    return -1;
}

static void put_i32(unsigned char *p, int32_t v)
{
    for (int i = 0; i < 4; ++i) p[i] = (unsigned char)((uint32_t)v >> (8 * i));
}

/* Both entry points fail with one line that starts with the path and holds `want` (`want2` too if given). */
static void expect_bad(const char *path, const char *want, const char *want2, int header_ok)
{
    char err[512] = "";
    io_exr_info info;
    int r = io_exr_read_info(path, &info, err, sizeof err);
    if (header_ok) {
        CHECK(r == 0, "%s: header should read: %s", path, err);
        if (r == 0) io_exr_info_free(&info);
    } else {
        CHECK(r != 0 && strstr(err, path) == err && strstr(err, want) && (!want2 || strstr(err, want2)) &&
                  !strchr(err, '\n'),
              "info: '%s' should say '%s'", err, want);
        CHECK(info.channels == NULL && info.channel_count == 0, "a failed info is zeroed");
    }
    const char *names[1] = {"G"};
    float *out = (float *)calloc(64 * 64, sizeof(float));
    err[0] = '\0';
    r = io_exr_read_channels(path, names, 1, out, err, sizeof err);
    CHECK(r != 0 && strstr(err, path) == err && strstr(err, want) && (!want2 || strstr(err, want2)) &&
              !strchr(err, '\n'),
          "channels: '%s' should say '%s'", err, want);
    free(out);
    printf("  bad file: %s\n", err);
}

static void test_bad_files(void)
{
    char good[256];
    snprintf(good, sizeof good, "%s", tmp_path("good.exr"));
    tw_part P = {.name = "p", .compression = EXR_COMPRESSION_ZIPS, .w = 64, .h = 64, .nch = 2, .smooth = 1,
                 .ch = {{"G", EXR_PIXEL_HALF}, {"R", EXR_PIXEL_FLOAT}}}; /* smooth: the chunks really compress */
    CHECK(tw_write(good, &P, 1) == 0, "write %s", good);
    size_t n = 0;
    unsigned char *b = slurp(good, &n);
    CHECK(b && n > 1000, "read back %s", good);
    if (!b) return;
    unsigned char *m = (unsigned char *)malloc(n + 64);
    const char *p;

    expect_bad(tmp_path("missing.exr"), "cannot open", "No such file", 0);
    expect_bad(g_dir, "not a regular file", NULL, 0);
    spit(p = tmp_path("empty.exr"), "", 0);
    expect_bad(p, "not an OpenEXR file", NULL, 0);
    spit(p = tmp_path("png.exr"), "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
    expect_bad(p, "not an OpenEXR file", NULL, 0);
    spit(p = tmp_path("magic_only.exr"), b, 4);
    expect_bad(p, "corrupt or unsupported EXR header", NULL, 0);
    spit(p = tmp_path("header_cut.exr"), b, 120);
    expect_bad(p, "corrupt or unsupported EXR header", NULL, 0);

    /* Data windows: too wide, too many pixels (within the side limit), negative. */
    static const char dwtag[] = "dataWindow\0box2i\0\x10\0\0\0";
    long dw = find_bytes(b, n, dwtag, sizeof dwtag - 1);
    CHECK(dw > 0, "dataWindow attribute found");
    if (dw > 0) {
        unsigned char *box = m + dw + sizeof dwtag - 1; /* xmin ymin xmax ymax */
        memcpy(m, b, n);
        put_i32(box + 8, 99999);
        spit(p = tmp_path("dw_wide.exr"), m, n);
        expect_bad(p, "data window is 100000x64", "accepted", 0);
        memcpy(m, b, n);
        put_i32(box + 8, 59999), put_i32(box + 12, 59999);
        spit(p = tmp_path("dw_area.exr"), m, n);
        expect_bad(p, "data window is 60000x60000", "268435456", 0);
        memcpy(m, b, n);
        put_i32(box + 0, 10), put_i32(box + 8, 5);
        spit(p = tmp_path("dw_neg.exr"), m, n);
        expect_bad(p, "EXR", NULL, 0); /* the library or we: either way one line */
        /* 16384 x 16384 is accepted by size, but an 11 kB file cannot hold its chunk table (16384 chunks of one
           line): refused by the header reader, before a caller allocates a 1 GiB buffer for it. */
        memcpy(m, b, n);
        put_i32(box + 8, 16383), put_i32(box + 12, 16383);
        spit(p = tmp_path("dw_big.exr"), m, n);
        expect_bad(p, "chunk table needs 131072 bytes", NULL, 0);
    }

    /* Chunks: cut short, offset past the end, compressed bytes scrambled. */
    spit(p = tmp_path("cut_tail.exr"), b, n - 200);
    expect_bad(p, "truncated or corrupt chunk", "rows", 1);
    exr_context_t ctxt = NULL;
    exr_chunk_info_t ci;
    CHECK(exr_start_read(&ctxt, good, NULL) == EXR_ERR_SUCCESS &&
              exr_read_scanline_chunk_info(ctxt, 0, 30, &ci) == EXR_ERR_SUCCESS,
          "chunk info of %s", good);
    exr_finish(&ctxt);
    unsigned char off[8];
    /* The table holds the chunk's start; data_offset is past its 8-byte leader (y, packed size). */
    for (int i = 0; i < 8; ++i) off[i] = (unsigned char)((ci.data_offset - 8) >> (8 * i));
    long at = find_bytes(b, n, off, 8);
    CHECK(at > 0, "offset table entry found");
    if (at > 0) {
        memcpy(m, b, n);
        m[at + 3] = 0x7f; /* far past the end */
        spit(p = tmp_path("offset_far.exr"), m, n);
        /* OpenEXRCore rebuilds a damaged offset table from the chunks' own leaders: then the pixels are right. */
        char e2[512] = "";
        const char *g[1] = {"G"};
        float want[64 * 64], got[64 * 64];
        CHECK(io_exr_read_channels(good, g, 1, want, e2, sizeof e2) == 0, "%s", e2);
        if (io_exr_read_channels(p, g, 1, got, e2, sizeof e2) == 0)
            CHECK(memcmp(got, want, sizeof got) == 0, "%s: rebuilt table read wrong pixels", p);
        else
            CHECK(strstr(e2, p) == e2 && strstr(e2, "chunk") && !strchr(e2, '\n'), "%s", e2);
    }
    memcpy(m, b, n);
    for (size_t i = ci.data_offset + 2; i < ci.data_offset + ci.packed_size && i < n; i += 3) m[i] ^= 0x5a;
    spit(p = tmp_path("scrambled.exr"), m, n);
    expect_bad(p, "corrupt ZIPS-compressed chunk", NULL, 1);

    /* A subsampled channel (4:2:0 chroma style) is refused by name; the full-resolution ones beside it read. */
    tw_part sub = {.name = "s", .compression = EXR_COMPRESSION_ZIP, .w = 16, .h = 8, .nch = 2, .sampling = 2,
                   .ch = {{"Y", EXR_PIXEL_HALF}, {"BY", EXR_PIXEL_HALF}}};
    p = tmp_path("subsampled.exr");
    CHECK(tw_write(p, &sub, 1) == 0, "write %s", p);
    {
        char e3[512] = "";
        const char *by[1] = {"BY"}, *y[1] = {"Y"};
        float o[16 * 8];
        CHECK(io_exr_read_channels(p, by, 1, o, e3, sizeof e3) != 0 && strstr(e3, "'BY' is subsampled (2x2)"), "%s", e3);
        CHECK(io_exr_read_channels(p, y, 1, o, e3, sizeof e3) == 0, "%s", e3);
        for (int i = 0; i < 16 * 8; ++i)
            CHECK(o[i] == tw_expect(tw_bits(0, 0, i % 16, i / 16, EXR_PIXEL_HALF, 0), EXR_PIXEL_HALF), "Y %d", i);
    }

    /* A channel that is not there: the message lists what is. */
    char err[512] = "";
    const char *names[2] = {"G", "ViewLayer.Position.X"};
    float out[64 * 64 * 2];
    CHECK(io_exr_read_channels(good, names, 2, out, err, sizeof err) != 0 &&
              strstr(err, "no channel 'ViewLayer.Position.X' (the file has: G, R)"),
          "%s", err);
    CHECK(io_exr_read_channels(good, names, 0, out, err, sizeof err) != 0, "zero channels");
    CHECK(io_exr_read_channels(good, NULL, 1, out, err, sizeof err) != 0, "no names");
    CHECK(io_exr_read_channels(good, names, 1, NULL, err, sizeof err) != 0, "no output");
    CHECK(io_exr_read_info(good, NULL, err, sizeof err) != 0, "no info");
    CHECK(io_exr_read_info(NULL, &(io_exr_info){0}, err, sizeof err) != 0, "no path");
    io_exr_info info;
    CHECK(io_exr_read_info(good, &info, NULL, 0) == 0, "no err buffer is fine");
    io_exr_info_free(&info);
    free(m);
    free(b);
}

/* Every file given (the regression inputs: what the fuzzers found, and one of each hostile class) must fail with
   one line or read cleanly: the run itself is the check under ASan (tests/sanitize.sh) or valgrind. */
static int check_files(int argc, char **argv)
{
    for (int i = 0; i < argc; ++i) {
        char err[512] = "";
        io_exr_info info;
        if (io_exr_read_info(argv[i], &info, err, sizeof err) == 0) {
            long long px = (long long)info.width * info.height;
            if (px <= (1 << 22) && info.channel_count > 0) {
                const char **names = (const char **)malloc((size_t)info.channel_count * sizeof *names);
                float *out = (float *)malloc((size_t)px * (size_t)info.channel_count * sizeof(float));
                for (int c = 0; names && c < info.channel_count; ++c) names[c] = info.channels[c].name;
                if (names && out && io_exr_read_channels(argv[i], names, info.channel_count, out, err, sizeof err))
                    CHECK(err[0] && !strchr(err, '\n'), "%s: empty or multi-line message", argv[i]);
                free(names);
                free(out);
            }
            io_exr_info_free(&info);
        } else {
            CHECK(err[0] && !strchr(err, '\n') && strstr(err, argv[i]) == err, "%s: message '%s'", argv[i], err);
        }
    }
    printf("%d regression files read cleanly\n", argc);
    return check_failures ? 1 : 0;
}

/* --dir DIR: check_files on every file in DIR (but README*). */
static int check_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        perror(dir);
        return 1;
    }
    char *paths[512];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < 512) {
        if (e->d_name[0] == '.' || strncmp(e->d_name, "README", 6) == 0) continue;
        size_t len = strlen(dir) + strlen(e->d_name) + 2;
        paths[n] = (char *)malloc(len);
        snprintf(paths[n++], len, "%s/%s", dir, e->d_name);
    }
    closedir(d);
    int r = n ? check_files(n, paths) : (fprintf(stderr, "%s: no files\n", dir), 1);
    for (int i = 0; i < n; ++i) free(paths[i]);
    return r;
}

int main(int argc, char **argv)
{
    if (argc > 2 && strcmp(argv[1], "--files") == 0) return check_files(argc - 2, argv + 2);
    if (argc == 3 && strcmp(argv[1], "--dir") == 0) return check_dir(argv[2]);
    int keep = argc == 2 && strcmp(argv[1], "--keep") == 0; /* leave the files for a look (or new regressions) */
    snprintf(g_dir, sizeof g_dir, "/tmp/vksky_exr_read.%ld", (long)getpid());
    if (mkdir(g_dir, 0700) != 0) {
        perror(g_dir);
        return 1;
    }
    int have_oiio = have_tool("oiiotool");
    test_codecs();
    test_b44(have_oiio);
    test_b44_edge_tiles();
    test_dwa(have_oiio);
    test_multipart();
    test_exrmultipart();
    test_layers_roundtrip(have_oiio);
    test_bad_files();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    if (keep)
        printf("files kept in %s\n", g_dir);
    else if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", g_dir);
    printf("%d checks, %d failures\n", check_count, check_failures);
    if (!check_failures && g_skipped) printf("SKIP: %d section(s) need a tool that is not installed\n", g_skipped);
    return check_failures ? 1 : g_skipped ? 77 : 0;
}
