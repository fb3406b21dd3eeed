/* The composite in spectral colour (composite_spectral.h). */
#include "app/runs/composite_spectral.h"
#include "app/runs/stop.h"
#include "io/parts.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GROUPS_MAX 16   /* 48 wavelengths, three to a pass */
#define PER_PASS 3u     /* the layers are RGB: three wavelengths to a pass */
#define FP16_MAX 65504.0f   /* half's largest finite value, the composite pass's clamp (composite.comp `store`) */

static const char *const LAYER_NAMES[VKSKY_COMPOSITE_LAYERS] = {"", "sky", "sun_disk", "transmittance", "rayleigh", "mie"};

typedef struct spectral_groups {
    uint32_t count;
    vksky_scene *scene[GROUPS_MAX];
    vksky_renderer *r[GROUPS_MAX];
    vksky_composite *c[GROUPS_MAX];
    /* light[k][c][q]: linear Rec.709 channel q per unit of group k's channel c in a light layer (its XYZ weight
     * through the Rec.709 matrix: the sum is linear, so summing RGB is summing XYZ and converting once).
     * through[k][c][q]: the same weight divided by its sum over every wavelength: the transmittance's share. */
    float light[GROUPS_MAX][PER_PASS][3];
    float through[GROUPS_MAX][PER_PASS][3];
} spectral_groups;

static void groups_destroy(spectral_groups *g)
{
    for (uint32_t k = 0; k < g->count; ++k) {
        vksky_composite_destroy(g->c[k]);
        vksky_renderer_destroy(g->r[k]);
        vksky_scene_destroy(g->scene[k]);
    }
    g->count = 0;
}

/* Each group's LUTs into the LUT cache, once its frames are done: a miss computed them in the first band, and the
 * next composite of the same medium (the frames of a render sequence, a test's second run) uploads them. Nothing on a
 * hit or without a cache directory. */
static int groups_store_luts(const spectral_groups *g)
{
    for (uint32_t k = 0; k < g->count; ++k)
        if (vksky_renderer_store_luts(g->r[k]) != VKSKY_SUCCESS) return 1;
    return 0;
}

/* One renderer (the LUTs of the group's medium, kept for every band) and one composite pass per group. */
static int groups_create(spectral_groups *g, vksky_context *ctx, const vksky_scene *scene, int wavelengths,
                         const vksky_composite_desc *desc, const composite_view *view, uint32_t whole_height,
                         uint32_t view_flags)
{
    uint32_t count = vksky_spectral_group_count((uint32_t)wavelengths, PER_PASS);
    if (count == 0 || count > GROUPS_MAX) {
        fprintf(stderr, "vksky: --composite: --spectral %d: not a count the GPU takes\n", wavelengths);
        return 1;
    }
    double total[3] = {0.0, 0.0, 0.0};
    for (uint32_t k = 0; k < count; ++k) {
        double xyz[4][3];
        if (vksky_scene_spectral_group(scene, (uint32_t)wavelengths, PER_PASS, k, &g->scene[k], xyz, NULL) !=
            VKSKY_SUCCESS)
            return 1;
        g->count = k + 1;
        for (uint32_t c = 0; c < PER_PASS; ++c) {
            double rgb[3];
            vksky_spectral_xyz_to_rec709(xyz[c], rgb);
            for (int q = 0; q < 3; ++q) g->light[k][c][q] = (float)rgb[q], total[q] += rgb[q];
        }
        /* The composite's renderer: the LUTs only, in the lesson's units (as the RGB composite's, composite_app.c). */
        vksky_renderer_desc rd = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_LUTS_ONLY, .width = 1,
                                  .height = 1, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "scene",
                                  .units = VKSKY_UNITS_RELATIVE, .scene = g->scene[k]};
        vksky_composite_desc cd = *desc;
        cd.slots = 1;
        if (vksky_renderer_create(ctx, &rd, &g->r[k]) != VKSKY_SUCCESS ||
            vksky_composite_create(g->r[k], &cd, &g->c[k]) != VKSKY_SUCCESS ||
            vksky_composite_set_view(g->c[k], view, whole_height, view_flags, NULL) != VKSKY_SUCCESS)
            return 1;
    }
    for (uint32_t k = 0; k < count; ++k)
        for (uint32_t c = 0; c < PER_PASS; ++c)
            for (int q = 0; q < 3; ++q) g->through[k][c][q] = (float)(g->light[k][c][q] / total[q]);
    return 0;
}

/* A band's sums: layers 1..5 (RGBA floats, alpha 1, as the RGB pass stores them) and the composite (layer 0). */
typedef struct band_sum {
    const spectral_groups *g;
    uint32_t group;               /* the group being added (add_group) */
    const float *beauty;          /* the band's core rows of the render (RGBA, premultiplied) */
    bool oriented;
    float *layer[VKSKY_COMPOSITE_LAYERS];
} band_sum;

static void add_group(void *user, size_t part, size_t begin, size_t end)
{
    (void)part;
    const band_sum *s = user;
    const spectral_groups *g = s->g;
    uint32_t k = s->group;
    for (uint32_t L = 1; L < VKSKY_COMPOSITE_LAYERS; ++L) {
        const float *src = vksky_composite_layer(g->c[k], 0, L);
        const float(*w)[3] = L == 3 ? g->through[k] : g->light[k];   /* layer 3: the transmittance */
        float *dst = s->layer[L];
        for (size_t i = begin; i < end; ++i) {
            const float *v = src + 4 * i;
            float *d = dst + 4 * i;
            if (k == 0) d[0] = d[1] = d[2] = 0.0f, d[3] = 1.0f;
            for (uint32_t c = 0; c < PER_PASS; ++c)
                for (int q = 0; q < 3; ++q) d[q] += w[c][q] * v[c];
        }
    }
}

static float clampf(float v, float lo, float hi) { return v < lo ? lo : v > hi ? hi : v; }

/* The layers within half's range, then the composite from them by the coverage identity, with the pass's reading of
 * the beauty (a non-finite value as 0, alpha clamped to [0, 1]). A light layer keeps a negative channel where its
 * colour lies outside Rec.709's gamut (a sunset's Mie light in the blue), as a spectral still's pixels do: clamping
 * each layer would bias its colour and break sky = rayleigh + mie (+ the lit ground). The transmittance is kept
 * non-negative, as a fraction of light must be. */
static void resolve(void *user, size_t part, size_t begin, size_t end)
{
    (void)part;
    const band_sum *s = user;
    for (size_t i = begin; i < end; ++i) {
        for (uint32_t L = 1; L < VKSKY_COMPOSITE_LAYERS; ++L)
            for (int q = 0; q < 3; ++q)
                s->layer[L][4 * i + q] = clampf(s->layer[L][4 * i + q], L == 3 ? 0.0f : -FP16_MAX, FP16_MAX);
        float beauty[4];
        for (int q = 0; q < 4; ++q) beauty[q] = isfinite(s->beauty[4 * i + q]) ? s->beauty[4 * i + q] : 0.0f;
        float alpha = clampf(beauty[3], 0.0f, 1.0f), *out = s->layer[0] + 4 * i;
        for (int q = 0; q < 3; ++q) {
            float rgb = beauty[q] * s->layer[3][4 * i + q] + alpha * (s->layer[4][4 * i + q] + s->layer[5][4 * i + q]) +
                        s->layer[1][4 * i + q] + s->layer[2][4 * i + q];
            out[q] = clampf(rgb, -FP16_MAX, FP16_MAX);
        }
        out[3] = s->oriented ? 1.0f : clampf(beauty[3], -FP16_MAX, FP16_MAX);
    }
}

/* One band through every group: fill(user, inputs) writes the band's inputs into each group's slot, the groups'
 * layers are summed into s's layers and resolved (`pixels`: the band's core, its first rows). 0, or 1. */
static int sum_band(const spectral_groups *g, host_commands *h, int first_row, size_t pixels,
                    void (*fill)(void *user, float *inputs), void *user, FILE *trace, band_sum *s)
{
    for (uint32_t k = 0; k < g->count; ++k) {
        fill(user, vksky_composite_inputs(g->c[k], 0));
        vksky_composite_frame f = {.slot = 0, .first_row = first_row};   /* the band's first row of the whole image */
        if (composite_submit(h, g->r[k], g->c[k], &f, 1, trace, NULL) != 0) return 1;
        s->group = k;
        io_parts_run(pixels, 65536, add_group, s);
    }
    io_parts_run(pixels, 65536, resolve, s);
    return 0;
}

static void fill_band(void *user, float *inputs)
{
    const band_reader *b = user;
    band_reader_upload(b, inputs, b->band_rows);
}

int composite_spectral_bands(band_reader *b, host_commands *h, vksky_context *ctx, const vksky_scene *scene,
                             int wavelengths, const vksky_composite_desc *desc, const composite_view *view,
                             FILE *trace, io_exr_layers_stream *out)
{
    spectral_groups g = {0};
    size_t band_pixels = (size_t)b->width * (size_t)b->band_rows;
    float *sums = malloc(band_pixels * 4 * VKSKY_COMPOSITE_LAYERS * sizeof(float));
    int rc = sums ? groups_create(&g, ctx, scene, wavelengths, desc, view, (uint32_t)b->height, VKSKY_COMPOSITE_FAST)
                  : 1;
    if (!sums) fprintf(stderr, "vksky: --composite: out of memory for a band of %dx%d pixels\n", b->width, b->band_rows);
    band_sum s = {.g = &g, .oriented = view->oriented};
    for (uint32_t L = 0; L < VKSKY_COMPOSITE_LAYERS && sums; ++L) s.layer[L] = sums + (size_t)L * band_pixels * 4;
    for (int y0 = 0; y0 < b->height && rc == 0; y0 += b->band_rows) {
        if ((rc = band_reader_read(b, y0)) != 0 || (rc = band_reader_verdict(b, false)) != 0) break;
        const composite_band *band = &b->band;
        s.beauty = b->beauty + (size_t)(band->core_row - band->first_row) * (size_t)b->width * 4;
        if ((rc = sum_band(&g, h, y0, (size_t)band->core_rows * (size_t)b->width, fill_band, b, trace, &s)) != 0)
            break;
        char err[600];
        io_exr_band_layer layers[VKSKY_COMPOSITE_LAYERS];
        for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k)
            layers[k] = (io_exr_band_layer){LAYER_NAMES[k], k == 0 ? 4 : 3, 4, s.layer[k]};
        if (io_exr_layers_stream_rows(out, layers, band->core_rows, err, sizeof err) != 0) {
            fprintf(stderr, "vksky: --render: %s\n", err);
            rc = 1;
        }
        if (rc == 0 && stop_requested()) rc = 1;   /* SIGINT/SIGTERM: no file at the output path */
    }
    if (rc == 0) rc = band_reader_verdict(b, true);
    if (rc == 0) rc = groups_store_luts(&g);
    if (rc) io_exr_layers_stream_abort(out);
    groups_destroy(&g);
    free(sums);
    return rc;
}

/* --aovs' frame: no geometry anywhere (beauty 0, position NaN), so every pixel's layers are the sky's. */
static void fill_empty(void *user, float *inputs)
{
    size_t n = *(const size_t *)user;
    for (size_t i = 0; i < n; ++i) {
        float *b = inputs + 4 * i, *p = inputs + 4 * (n + i);
        b[0] = b[1] = b[2] = b[3] = 0.0f;
        p[0] = p[1] = p[2] = p[3] = NAN;
    }
}

int composite_spectral_aovs(host_commands *h, vksky_context *ctx, const vksky_scene *scene, int wavelengths,
                            const vksky_composite_desc *desc, const composite_view *view, FILE *trace,
                            float **layers)
{
    *layers = NULL;
    spectral_groups g = {0};
    size_t n = (size_t)desc->width * desc->rows;
    float *sums = malloc(n * 4 * VKSKY_COMPOSITE_LAYERS * sizeof(float));
    float *zero = calloc(n * 4, sizeof(float));   /* the beauty the identity adds: none */
    int rc = sums && zero ? groups_create(&g, ctx, scene, wavelengths, desc, view, desc->rows,
                                          VKSKY_COMPOSITE_VIEW_ALTITUDE)
                          : 1;
    if (!sums || !zero) fprintf(stderr, "vksky: --aovs: out of memory\n");
    band_sum s = {.g = &g, .oriented = view->oriented, .beauty = zero};
    for (uint32_t L = 0; L < VKSKY_COMPOSITE_LAYERS && sums; ++L) s.layer[L] = sums + (size_t)L * n * 4;
    if (rc == 0) rc = sum_band(&g, h, 0, n, fill_empty, &n, trace, &s);
    if (rc == 0) rc = groups_store_luts(&g);
    groups_destroy(&g);
    free(zero);
    if (rc) free(sums);
    else *layers = sums;
    return rc;
}
