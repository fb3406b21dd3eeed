/* tools/tradeoff_aerial: the aerial-perspective trade (issue 12 item 2), measured: the per-pixel march against
 * Hillaire's froxel volume in several shapes, on seed 004's view (camera 218.8 m up, looking along azimuth 95,
 * pitch -3, 40 deg; sun 20 deg up at azimuth -60) over a synthetic frame that is geometry everywhere: the flat
 * ground where the pixel's ray meets it within 40 km, else a wall 12 km away. For each configuration:
 *   - GPU time: the composite frame's ap_volume + composite passes (timestamps; and submit -> fence wall time),
 *     median over --frames frames after warm-up, at --size;
 *   - error: every pixel of an --error-size frame against the converged CPU reference (ref_radiance_to_point):
 *     relative luminance error of the in-scattering S (mean, max: what the atmosphere adds, and all of a black
 *     surface's composite, the worst case; a brighter surface's composite is dominated by beauty T, whose error
 *     is smaller), max |dT|, max relative S per channel.
 * Converged LUTs and --steps march steps on both paths, so the figures are the method's, not the LUTs'.
 * Writes a CSV and, with --emit-table, the C table --aerial-perspective auto chooses from (src/app/quality/ap_trade_table.h).
 *
 * --classes (issue 28 item 7): the error on every view class below as well as seed 004's, and no timing (--frames 0
 * keeps the GPU times of the table built in); the table's error is then each method's worst class mean, so that
 * --max-error's promise holds on each class, and a CSV row per class and method.
 *
 *   tradeoff_aerial [--size WxH] [--error-size WxH] [--frames N] [--steps N] [--csv FILE] [--emit-table FILE]
 *                   [--classes] [--defaults]
 */
#include "app/quality/ap_trade_table.h"
#include "reference/ref_atmosphere.h"
#include "sky/composite.h"
#include "sky/submit.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double DEG = 3.14159265358979323846 / 180.0;
static const double SUN_RADIUS = 0.5 * 0.53 * 3.14159265358979323846 / 180.0;
static const double GREY = 0.18;

typedef struct config { const char *name; bool volume; ap_volume_desc shape; } config;

static const config configs[] = {
    {"march", false, {0}},
    {"volume 16x16x16", true, {16, 16, 16, 32.0f, 2.0f}},
    {"volume 32x32x32", true, {32, 32, 32, 32.0f, 2.0f}},
    {"volume 32x32x32 linear", true, {32, 32, 32, 32.0f, 1.0f}},
    {"volume 32x32x64", true, {32, 32, 64, 32.0f, 2.0f}},
    {"volume 64x64x32", true, {64, 64, 32, 32.0f, 2.0f}},
    {"volume 64x64x64", true, {64, 64, 64, 32.0f, 2.0f}},
};
enum { CONFIG_COUNT = sizeof configs / sizeof configs[0] };

/* A view class: the camera's altitude and pitch, the sun's elevation (azimuth 95 and a 40 degree fov throughout;
 * the sun at azimuth -60), and the geometry: the flat ground within `ground_km`, else a wall `wall_km` away. */
typedef struct view_class {
    const char *name;
    double altitude_km, pitch_deg, sun_elevation_deg, ground_km, wall_km;
} view_class;

static const view_class classes[] = {
    {"seed 004 (218.8 m, 3 deg down, sun 20)", 0.2188, -3.0, 20.0, 40.0, 12.0},
    {"near steep ground (218.8 m, 35 deg down: ground 0.3-1.5 km)", 0.2188, -35.0, 20.0, 40.0, 12.0},
    {"grazing (2 m, level: ground to the horizon, wall 30 km)", 0.002, 0.0, 20.0, 40.0, 30.0},
    {"high altitude (10 km, 30 deg down)", 10.0, -30.0, 20.0, 60.0, 40.0},
    {"low sun (218.8 m, 3 deg down, sun 2)", 0.2188, -3.0, 2.0, 40.0, 12.0},
};
enum { CLASS_COUNT = sizeof classes / sizeof classes[0] };
static const view_class *view_now = &classes[0];
/* --defaults (issue 28 item 7): the march as `vksky --composite` runs it without --max-steps (--steps 32, the
 * segments' ramp of composite_push_fast: 4 steps at 0 km up to 32 at 40 km), not a fixed count. */
static bool composite_defaults = false;

static composite_view seed_view(int steps)
{
    composite_view v = {.km_per_unit = 1.0, .up_axis = 1, .camera = {0.0, view_now->altitude_km, 0.0},
                        .fov_y_deg = 40.0, .sun_azimuth_deg = -60.0, .sun_elevation_deg = view_now->sun_elevation_deg,
                        .steps = steps, .max_steps = composite_defaults ? 0 : steps, .steps_ramp_km = 100.0,
                        .sample_offset = 0.5, .step_distribution = 2.0};
    composite_view_orient_yaw_pitch(&v, 95.0, view_now->pitch_deg);
    return v;
}

/* Pixel (x, y)'s ray (world = vksky's local frame here: Y up, km, camera above the origin) and its point. */
static void pixel_point(const composite_view *v, int x, int y, int w, int h, double dir[3], double *dist)
{
    double ty = tan(0.5 * v->fov_y_deg * DEG), tx = ty * w / h;
    double nx = 2.0 * (x + 0.5) / w - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / h, n = 0.0;
    for (int k = 0; k < 3; ++k) dir[k] = v->forward[k] + nx * tx * v->right[k] + ny * ty * v->up[k], n += dir[k] * dir[k];
    for (int k = 0; k < 3; ++k) dir[k] /= sqrt(n);
    double t_ground = dir[1] < 0.0 ? v->camera[1] / -dir[1] : INFINITY;
    *dist = t_ground <= view_now->ground_km ? t_ground : view_now->wall_km;
}

static void fill_inputs(sky_composite *c, const composite_view *v)
{
    int w = (int)c->width, h = (int)c->height;
    float *in = sky_composite_inputs(c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double d[3], t;
            pixel_point(v, x, y, w, h, d, &t);
            float *b = in + 4 * ((size_t)y * w + x), *p = in + 4 * ((size_t)(h + y) * w + x);
            b[0] = b[1] = b[2] = (float)GREY, b[3] = 1.0f;
            for (int k = 0; k < 3; ++k) p[k] = (float)(v->camera[k] + d[k] * t);
            p[3] = 1.0f;
        }
}

static double median(double *a, int n)
{
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0 && a[j - 1] > a[j]; --j) { double t = a[j]; a[j] = a[j - 1], a[j - 1] = t; }
    return a[n / 2];
}

static double luminance(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

typedef struct row { double gpu_ms, wall_ms, err_mean, err_max, dT_max, dS_max; } row;

/* The error of one method on the current view class against the reference at every pixel of an ew x eh frame. */
static int measure_error(sky_renderer *r, const model_atmosphere *earth, const config *cf, const composite_view *v,
                         int ew, int eh, const ref_aerial *ref, row *rw)
{
    char err[256];
    sky_composite c;
    CompositePush push;
    if (sky_composite_create(&c, r, (uint32_t)ew, (uint32_t)eh, cf->volume ? &cf->shape : NULL, err, sizeof err)) {
        fprintf(stderr, "tradeoff_aerial: %s: %s\n", cf->name, err);
        return 1;
    }
    composite_push(v, earth->bottom_radius, (uint32_t)ew, (uint32_t)eh, &push);
    if (composite_defaults) composite_push_fast(v, &push);
    fill_inputs(&c, v);
    sky_composite_render(r, &c, &push, 1);
    double sum = 0.0;
    size_t en = (size_t)ew * eh;
    for (size_t i = 0; i < en; ++i) {
        const float *T = sky_composite_layer(&c, VKSKY_AOV_TRANSMITTANCE) + 4 * i;
        const float *R = sky_composite_layer(&c, VKSKY_AOV_RAYLEIGH) + 4 * i;
        const float *M = sky_composite_layer(&c, VKSKY_AOV_MIE) + 4 * i;
        double L[3], Lr[3];
        for (int k = 0; k < 3; ++k) {
            double S = (double)R[k] + M[k], Sr = ref[i].rayleigh[k] + ref[i].mie[k];
            L[k] = S;
            Lr[k] = Sr;
            rw->dT_max = fmax(rw->dT_max, fabs(T[k] - ref[i].transmittance[k]));
            rw->dS_max = fmax(rw->dS_max, fabs(S - Sr) / fmax(Sr, 1e-9));
        }
        double e = fabs(luminance(L) - luminance(Lr)) / luminance(Lr);
        sum += e;
        rw->err_max = fmax(rw->err_max, e);
    }
    rw->err_mean = sum / (double)en;
    sky_composite_destroy(&c, r);
    return 0;
}

static void time_config(sky_renderer *r, const model_atmosphere *earth, const config *cf, const composite_view *v,
                        int tw, int th, int frames, double *ms, row *rw)
{
    char err[256];
    sky_composite c;
    CompositePush push;
    double read[GPU_TIMER_MAX];
    if (sky_composite_create(&c, r, (uint32_t)tw, (uint32_t)th, cf->volume ? &cf->shape : NULL, err, sizeof err)) {
        fprintf(stderr, "tradeoff_aerial: %s: %s\n", cf->name, err);
        exit(1);
    }
    composite_push(v, earth->bottom_radius, (uint32_t)tw, (uint32_t)th, &push);
    if (composite_defaults) composite_push_fast(v, &push);
    fill_inputs(&c, v);
    for (int i = 0; i < 3; ++i) sky_composite_render(r, &c, &push, 1);   /* warm-up */
    for (int i = 0; i < frames; ++i) {
        ms[frames + i] = sky_composite_render(r, &c, &push, 1);
        uint32_t n = gpu_timer_read(r->ctx, &r->timer, read);
        ms[i] = 0.0;
        for (uint32_t k = 0; k < n; ++k)
            if (!strcmp(r->timer.names[k], "ap_volume") || !strcmp(r->timer.names[k], "composite")) ms[i] += read[k];
    }
    rw->gpu_ms = median(ms, frames);
    rw->wall_ms = median(ms + frames, frames);
    sky_composite_destroy(&c, r);
}

int main(int argc, char **argv)
{
    int tw = 1920, th = 1080, ew = 48, eh = 27, frames = 30, steps = 128;
    bool by_class = false;
    const char *csv = "tradeoff_aerial.csv", *table = NULL;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--classes")) { by_class = true; continue; }
        if (!strcmp(a, "--defaults")) { composite_defaults = true, steps = 32; continue; }
        if (!val) { fprintf(stderr, "tradeoff_aerial: %s needs a value\n", a); return 2; }
        if (!strcmp(a, "--size") && sscanf(val, "%dx%d", &tw, &th) == 2 && tw > 0 && th > 0) ++i;
        else if (!strcmp(a, "--error-size") && sscanf(val, "%dx%d", &ew, &eh) == 2 && ew > 0 && eh > 0) ++i;
        else if (!strcmp(a, "--frames") && (frames = atoi(val)) >= 0) ++i;
        else if (!strcmp(a, "--steps") && (steps = atoi(val)) > 0) ++i;
        else if (!strcmp(a, "--csv")) csv = val, ++i;
        else if (!strcmp(a, "--emit-table")) table = val, ++i;
        else { fprintf(stderr, "tradeoff_aerial: bad argument %s %s\n", a, val); return 2; }
    }
    gpu_context ctx;
    gpu_context_desc cdesc = {.device_index = -1};
    if (gpu_context_create(&ctx, &cdesc) != 0) return 1;
    sky_renderer_desc desc = {.width = 8, .height = 8, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    desc.lut = sky_lut_quality_default();   /* converged LUTs, as tests/aerial_points.h */
    desc.lut.lut_f32 = true;
    desc.lut.multiscatter_sqrt_dirs = 64, desc.lut.multiscatter_steps = 64, desc.lut.multiscatter_size = 64;
    sky_renderer r;
    sky_renderer_create(&r, &ctx, &desc);
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    sky_renderer_set_atmosphere(&r, &earth, SUN_RADIUS);
    fprintf(stderr, "tradeoff_aerial: device %s, timing at %dx%d (%d frames), error at %dx%d, %d steps%s\n",
            ctx.props.deviceName, tw, th, frames, ew, eh, steps, by_class ? ", every view class" : "");

    FILE *out = fopen(csv, "w");
    if (!out) { fprintf(stderr, "tradeoff_aerial: cannot write %s\n", csv); return 1; }
    fprintf(out, "device,class,config,width,height,steps,gpu_ms,wall_ms,err_mean,err_max,dT_max,dS_max\n");
    row rows[CONFIG_COUNT], worst[CONFIG_COUNT];
    memset(worst, 0, sizeof worst);
    size_t en = (size_t)ew * eh;
    ref_aerial *ref = malloc(en * sizeof *ref);
    double *ms = calloc((size_t)(frames > 0 ? frames : 1) * 2, sizeof *ms);
    ref_quality q = ref_quality_converged();
    for (int vc = 0; vc < (by_class ? CLASS_COUNT : 1); ++vc) {
        view_now = &classes[vc];
        composite_view v = seed_view(steps);
        /* The reference at every error pixel. */
        double el = view_now->sun_elevation_deg * DEG, sun[3] = {cos(el) * cos(-60.0 * DEG), sin(el),
                                                                 cos(el) * sin(-60.0 * DEG)};
        for (int y = 0; y < eh; ++y)
            for (int x = 0; x < ew; ++x) {
                double d[3], t;
                pixel_point(&v, x, y, ew, eh, d, &t);
                double dl[3];   /* the reference works in vksky's local frame (north, up, east) */
                composite_world_to_local(v.up_axis, d, dl);
                ref_radiance_to_point(&earth, view_now->altitude_km, dl, sun, t, q, &ref[(size_t)y * ew + x]);
            }
        fprintf(stderr, "class: %s\n", view_now->name);
        for (int ci = 0; ci < CONFIG_COUNT; ++ci) {
            const config *cf = &configs[ci];
            row *rw = &rows[ci];
            *rw = (row){0};
            if (measure_error(&r, &earth, cf, &v, ew, eh, ref, rw)) return 1;
            if (vc == 0 && frames > 0) time_config(&r, &earth, cf, &v, tw, th, frames, ms, rw);
            if (vc == 0 && frames == 0) rw->gpu_ms = ap_trade_table[ci].gpu_ms;   /* the table's measured times */
            if (vc == 0) worst[ci] = *rw;
            worst[ci].err_mean = fmax(worst[ci].err_mean, rw->err_mean);
            worst[ci].err_max = fmax(worst[ci].err_max, rw->err_max);
            fprintf(out, "\"%s\",\"%s\",%s,%d,%d,%d,%.4f,%.4f,%.5f,%.5f,%.2e,%.5f\n", ctx.props.deviceName,
                    view_now->name, cf->name, tw, th, steps, rw->gpu_ms, rw->wall_ms, rw->err_mean, rw->err_max,
                    rw->dT_max, rw->dS_max);
            fflush(out);
            fprintf(stderr, "  %-24s gpu %8.3f ms | S lum err mean %5.2f%% max %5.2f%% | max dT %.1e max dS %5.2f%%\n",
                    cf->name, rw->gpu_ms, 100 * rw->err_mean, 100 * rw->err_max, rw->dT_max, 100 * rw->dS_max);
        }
    }
    fclose(out);
    if (table) {
        FILE *t = fopen(table, "w");
        if (!t) { fprintf(stderr, "tradeoff_aerial: cannot write %s\n", table); return 1; }
        fprintf(t, "/* The aerial-perspective trade, --aerial-perspective auto chooses from it (options_composite.c). Errors\n"
                   " * measured by tools/tradeoff_aerial%s on %s: mean relative luminance error of the\n"
                   " * in-scattering at %dx%d vs the converged reference, %d march steps%s. GPU ms: ap_volume + composite\n"
                   " * at 1920x1080 on an NVIDIA H100 (median of 60 frames). Regenerate: tradeoff_aerial --emit-table. */\n"
                   "#ifndef VKSKY_APP_AP_TRADE_TABLE_H\n#define VKSKY_APP_AP_TRADE_TABLE_H\n"
                   "typedef struct ap_trade { unsigned size[3]; double range_km, distribution, gpu_ms, err_mean; } ap_trade;\n"
                   "/* size 0x0x0: the per-pixel march. */\nstatic const ap_trade ap_trade_table[] = {\n",
                by_class ? " --classes" : "", ctx.props.deviceName, ew, eh, steps,
                by_class ? "; each method's worst view class (docs/aerial_perspective.md)" : "");
        for (int ci = 0; ci < CONFIG_COUNT; ++ci) {
            const ap_volume_desc *sh = &configs[ci].shape;
            fprintf(t, "    {{%u, %u, %u}, %.1f, %.1f, %.4f, %.5f},   /* %s */\n", sh->width, sh->height, sh->depth,
                    sh->range_km, sh->distribution, worst[ci].gpu_ms, worst[ci].err_mean, configs[ci].name);
        }
        fprintf(t, "};\nenum { AP_TRADE_COUNT = %d };\n#endif\n", CONFIG_COUNT);
        fclose(t);
    }
    free(ms), free(ref);
    sky_renderer_destroy(&r);
    gpu_context_destroy(&ctx);
    return 0;
}
