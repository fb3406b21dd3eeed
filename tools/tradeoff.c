/* tools/tradeoff: the speed/accuracy trade, measured.
 *
 * For every configuration (the presets and a sweep of the knobs) and every scene of the fixed set (noon,
 * afternoon, sunset (sun +2), twilight (-4), 10 km at the horizon, 400 km at the limb, the sun on the horizon (0),
 * twilight at -2; quality_scenes):
 *   - GPU time: per-pass timestamps, median over --frames frames after warm-up, at --size (no readback);
 *   - error: a small frame (--error-size, bloom off) against the converged CPU reference of the same view:
 *     relative luminance error over sky pixels (mean, p95, max) and mean CIEDE2000 of the tone-mapped images.
 *     With --error-render WxH the frame is rendered at WxH and compared at an --error-size grid of its pixels
 *     (the reference traced through those very pixels): the error of a full-size frame, whose render scale and
 *     upsample act on its own pixel spacing, at the reference cost of the small grid.
 *   - --cost cpu: the table's cost is the process's CPU ms per whole frame (bloom and tone map included) instead
 *     of the sky's GPU ms: on a CPU device (lavapipe) the frame's work whatever else the machine runs.
 *   - horizon: the error over the pixels within 2 px of the analytic horizon against the per-pixel march (ultra)
 *     of the same view at --horizon-size (default 480x270): max and mean (tools/tradeoff_horizon.h; issue 26).
 *     --emit-horizon-table FILE measures only that, for every configuration and scene, and writes the table
 *     --max-error also checks (src/app/quality/quality_horizon_table.h): a configuration whose horizon error on a class
 *     exceeds the bound is refused there.
 * Writes a CSV (plot it with tools/plot_tradeoff.sh) and optionally the C table that --max-error chooses from.
 *
 *   tradeoff [--size WxH] [--error-size WxH] [--error-render WxH] [--frames N] [--csv FILE]
 *            [--emit-table FILE] [--cost gpu|cpu] [--configs a,b,...] [--scenes noon,...]
 *            [--device N] [--sun-visibility penumbra|lesson-fade] [--horizon-size WxH]
 *            [--emit-horizon-table FILE] [--horizon-reference PRESET] [--validate]
 *   --horizon-reference PRESET: the horizon band's reference (default ultra, the table's); ctest horizon_band uses
 *     high, whose 128x128 multi-scattering LUT is not minutes of lavapipe's time (issue 26).
 *   --validate: validation + synchronization validation; any message makes the exit status 1.
 */
#include "app/runs/cpu_time.h"
#include "app/quality/quality.h"
#include "io/half_float.h"
#include "reference/metrics.h"
#include "sky/submit.h"
#include "tradeoff_horizon.h"
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const double DEG = 3.14159265358979323846 / 180.0;
static const double SUN_RADIUS = 0.5 * 0.53 * 3.14159265358979323846 / 180.0;

typedef struct row {
    const char *config;
    int scene;
    double sky_ms, frame_ms, wall_ms, cpu_ms;
    metrics_luminance err;
    double de2000;
    horizon_error horizon;
} row;

/* The colour axis of the trade (issue 32 item 5) for the scenes measured: each colour setting's worst CIEDE2000
 * against the 48-wavelength spectral reference (quality_color_table.h, tools/color_error) and the GPU's cost of it,
 * a whole frame per group of three wavelengths (docs/spectral.md). The presets' rows are the RGB row's. */
static void print_color_axis(float *const *measured)
{
    int settings[16], count = quality_color_settings(settings, 16);
    fprintf(stderr, "colour axis (worst CIEDE2000 vs the 48-wavelength spectral reference; every preset is RGB):\n");
    fprintf(stderr, "%-16s %-7s", "setting", "frames");
    for (int s = 0; s < QUALITY_SCENE_COUNT; ++s)
        if (measured[s]) fprintf(stderr, " %13s", quality_scenes[s].name);
    fprintf(stderr, "\n");
    for (int k = 0; k < count; ++k) {
        char name[24];
        snprintf(name, sizeof name, settings[k] ? "--spectral %d" : "RGB", settings[k]);
        fprintf(stderr, "%-16s %-7d", name, settings[k] ? (settings[k] + 2) / 3 : 1);
        for (int s = 0; s < QUALITY_SCENE_COUNT; ++s)
            if (measured[s]) fprintf(stderr, " %13.2f", quality_color_error(settings[k], s));
        fprintf(stderr, "\n");
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The error grid: w x h samples of a full_w x full_h frame, grid point i at pixel floor((i + 1/2) full / n) (the
 * identity when the frame is the grid's own size). */
typedef struct error_grid { int w, h, full_w, full_h; } error_grid;
static int grid_x(const error_grid *g, int i) { return (int)(((double)i + 0.5) * g->full_w / g->w); }
static int grid_y(const error_grid *g, int j) { return (int)(((double)j + 0.5) * g->full_h / g->h); }

/* --- The converged reference image of a scene (CPU, two threads) --- */
typedef struct ref_job {
    const model_atmosphere *a;
    const quality_scene *s;
    const error_grid *g;
    int w, h, next;
    float *rgba;
    pthread_mutex_t lock;
} ref_job;

static void *ref_rows(void *arg)
{
    ref_job *j = arg;
    double sun[3];
    ref_dir(0.0, j->s->sun_elevation_deg * DEG, sun);
    for (;;) {
        pthread_mutex_lock(&j->lock);
        int y = j->next++;
        pthread_mutex_unlock(&j->lock);
        if (y >= j->h) return NULL;
        for (int x = 0; x < j->w; ++x) {
            double dir[3], rgb[3];
            ref_pixel_dir(grid_x(j->g, x), grid_y(j->g, y), j->g->full_w, j->g->full_h, j->s->yaw_deg * DEG,
                          j->s->pitch_deg * DEG, j->s->fov_deg * DEG, dir);
            ref_sky_radiance(j->a, j->s->altitude_km, dir, sun, ref_quality_converged(), rgb);
            float *p = j->rgba + 4 * ((size_t)y * j->w + x);
            p[0] = (float)rgb[0], p[1] = (float)rgb[1], p[2] = (float)rgb[2], p[3] = 1.0f;
        }
    }
}

static float *reference_image(const model_atmosphere *a, const quality_scene *s, const error_grid *g)
{
    int w = g->w, h = g->h;
    ref_job j = {.a = a, .s = s, .g = g, .w = w, .h = h, .rgba = malloc(sizeof(float) * 4 * (size_t)w * h)};
    pthread_mutex_init(&j.lock, NULL);
    double up[3] = {0, 1, 0}, sun[3], rgb[3];
    ref_dir(0.0, s->sun_elevation_deg * DEG, sun);
    ref_sky_radiance(a, s->altitude_km, up, sun, ref_quality_converged(), rgb);   /* builds the Psi table once */
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int n = cores < 1 ? 1 : cores > 32 ? 32 : (int)cores;
    pthread_t t[32];
    for (int i = 0; i < n; ++i) pthread_create(&t[i], NULL, ref_rows, &j);
    for (int i = 0; i < n; ++i) pthread_join(t[i], NULL);
    pthread_mutex_destroy(&j.lock);
    return j.rgba;
}

/* Sky pixels, minus the sun's disc and its immediate surroundings (the reference excludes the disc). */
static void error_mask(const model_atmosphere *a, const quality_scene *s, const error_grid *g, unsigned char *mask)
{
    unsigned char *full = malloc((size_t)g->full_w * g->full_h);
    metrics_sky_mask(a, s->altitude_km, g->full_w, g->full_h, s->yaw_deg * DEG, s->pitch_deg * DEG, s->fov_deg * DEG,
                     full);
    double sun[3];
    ref_dir(0.0, s->sun_elevation_deg * DEG, sun);
    for (int y = 0; y < g->h; ++y)
        for (int x = 0; x < g->w; ++x) {
            double d[3];
            int px = grid_x(g, x), py = grid_y(g, y);
            ref_pixel_dir(px, py, g->full_w, g->full_h, s->yaw_deg * DEG, s->pitch_deg * DEG, s->fov_deg * DEG, d);
            mask[y * g->w + x] = full[(size_t)py * g->full_w + px];
            if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > cos(4.0 * SUN_RADIUS)) mask[y * g->w + x] = 0;
        }
    free(full);
}

static sky_renderer make_renderer(gpu_context *ctx, const quality_config *q, sky_view *v, int w, int h, bool readback,
                                  const model_atmosphere *a)
{
    sky_renderer_desc desc = {.width = (uint32_t)w, .height = (uint32_t)h, .bloom = v->bloom, .readback = readback,
                              .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    int bloom_mips = 5;
    desc.lut = sky_lut_quality_default();
    quality_apply(q, v, &desc.lut, &desc.render_scale, &bloom_mips, &desc.bloom_quarter);
    desc.bloom_mips = (uint32_t)bloom_mips;
    sky_renderer r;
    sky_renderer_create(&r, ctx, &desc);
    sky_renderer_set_atmosphere(&r, a, SUN_RADIUS);
    return r;
}

static void measure_time(gpu_context *ctx, const quality_config *q, const quality_scene *s, int w, int h, int frames,
                         const model_atmosphere *a, row *out)
{
    sky_view v = quality_scene_view(s);
    sky_renderer r = make_renderer(ctx, q, &v, w, h, false, a);
    frame_desc f = {.view = &v};
    for (int i = 0; i < 3; ++i) sky_renderer_render(&r, &f);    /* warm-up: shader compilation, clocks */
    double *sky = calloc((size_t)frames, sizeof(double)), *total = calloc((size_t)frames, sizeof(double)),
           *wall = calloc((size_t)frames, sizeof(double));
    double ms[GPU_TIMER_MAX];
    double cpu_start = process_cpu_ms();
    for (int i = 0; i < frames; ++i) {
        wall[i] = sky_renderer_render(&r, &f);
        uint32_t n = gpu_timer_read(ctx, &r.timer, ms);
        for (uint32_t k = 0; k < n; ++k) {
            total[i] += ms[k];
            if (!strcmp(r.timer.names[k], "sky") || !strcmp(r.timer.names[k], "skyview_lut")) sky[i] += ms[k];
        }
    }
    out->cpu_ms = (process_cpu_ms() - cpu_start) / frames;
    out->sky_ms = median(sky, frames);
    out->frame_ms = median(total, frames);
    out->wall_ms = median(wall, frames);
    free(sky), free(total), free(wall);
    sky_renderer_destroy(&r);
}

static void measure_error(gpu_context *ctx, const quality_config *q, const quality_scene *s, const error_grid *g,
                          const model_atmosphere *a, const float *ref, const unsigned char *mask, row *out)
{
    int w = g->w, h = g->h;
    sky_view v = quality_scene_view(s);
    v.bloom = false;
    sky_renderer r = make_renderer(ctx, q, &v, g->full_w, g->full_h, true, a);
    frame_desc f = {.view = &v};
    sky_renderer_render(&r, &f);
    size_t n = 4 * (size_t)w * h;
    float *gpu = malloc(sizeof(float) * n);
    const uint16_t *half = r.readback_linear.mapped;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c)
                gpu[4 * ((size_t)y * w + x) + c] =
                    io_half_to_float(half[4 * ((size_t)grid_y(g, y) * g->full_w + grid_x(g, x)) + c]);
    sky_renderer_destroy(&r);
    double max_ref = 0.0;
    for (size_t i = 0; i < (size_t)w * h; ++i)
        if (mask[i]) max_ref = fmax(max_ref, 0.2126 * ref[4 * i] + 0.7152 * ref[4 * i + 1] + 0.0722 * ref[4 * i + 2]);
    out->err = metrics_relative_luminance(gpu, ref, mask, w, h, 1e-3 * max_ref);
    unsigned char *a8 = malloc(n), *b8 = malloc(n);
    metrics_tonemap_srgb8(gpu, w, h, s->exposure_ev, VKSKY_TONEMAP_ACES, a8);
    metrics_tonemap_srgb8(ref, w, h, s->exposure_ev, VKSKY_TONEMAP_ACES, b8);
    out->de2000 = metrics_ciede2000_mean(a8, b8, mask, w, h);
    free(a8), free(b8), free(gpu);
}

static int parse_size(const char *s, int *w, int *h) { return sscanf(s, "%dx%d", w, h) == 2 && *w > 0 && *h > 0 ? 0 : -1; }

static bool wanted(const char *list, const char *name)
{
    if (!list) return true;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ',') && (p[n] == ',' || p[n] == 0)) return true;
    return false;
}

/* --emit-horizon-table: the horizon-band error of every configuration on every scene, nothing else. */
static int emit_horizon_table(gpu_context *ctx, const char *path, const char *configs, const char *scenes, int w, int h,
                              const model_atmosphere *a, const quality_config *reference)
{
    FILE *t = fopen(path, "w");
    if (!t) { fprintf(stderr, "tradeoff: cannot write %s\n", path); return 1; }
    fprintf(t, "/* Measured by tools/tradeoff --emit-horizon-table on %s: the relative luminance error over the pixels\n"
               " * within 2 px of the analytic horizon of a %dx%d frame against the per-pixel march (ultra) of the same\n"
               " * view, max and mean (tools/tradeoff_horizon.h). --max-error refuses a configuration whose max on a\n"
               " * class exceeds the bound. Regenerate: tradeoff --emit-horizon-table FILE. */\n",
            ctx->props.deviceName, w, h);
    fprintf(t, "typedef struct quality_horizon { const char *config; int scene; double max, mean; } quality_horizon;\n"
               "static const quality_horizon quality_horizon_table[] = {\n");
    for (int s = 0; s < QUALITY_SCENE_COUNT; ++s) {
        if (!wanted(scenes, quality_scenes[s].name)) continue;
        float *ref = horizon_frame(ctx, reference, &quality_scenes[s], w, h, a, SUN_RADIUS);
        for (int c = 0; c < 4 + quality_sweep_count; ++c) {
            const quality_config *q = c < 4 ? &quality_presets[c] : &quality_sweep[c - 4];
            if (!wanted(configs, q->name) || q->mode == SKY_CHOICE_FILL) continue;
            float *lum = horizon_frame(ctx, q, &quality_scenes[s], w, h, a, SUN_RADIUS);
            horizon_error e = horizon_band_error(lum, ref, &quality_scenes[s], w, h, a, SUN_RADIUS);
            free(lum);
            fprintf(t, "    {\"%s\", %d, %.5f, %.5f},\n", q->name, s, e.max, e.mean);
            fprintf(stderr, "%-36s %-13s horizon max %7.3f%% mean %7.3f%%\n", q->name, quality_scenes[s].name,
                    100 * e.max, 100 * e.mean);
        }
        free(ref);
    }
    fprintf(t, "};\nstatic const int quality_horizon_table_count =\n"
               "    (int)(sizeof quality_horizon_table / sizeof quality_horizon_table[0]);\n");
    fclose(t);
    unsigned messages = gpu_validation_message_count();
    gpu_context_destroy(ctx);
    if (messages) fprintf(stderr, "tradeoff: %u validation messages\n", messages);
    return messages ? 1 : 0;
}

int main(int argc, char **argv)
{
    int tw = 1920, th = 1080, ew = 96, eh = 54, rw = 0, rh = 0, frames = 30, device = -1, hw = 480, hh = 270;
    const char *csv = "tradeoff.csv", *table = NULL, *configs = NULL, *scenes = NULL, *horizon_table = NULL;
    bool cost_cpu = false, lesson = false, validate = false;
    const quality_config *horizon_ref = &quality_presets[3];
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--validate")) { validate = true; continue; }
        if (!v) { fprintf(stderr, "tradeoff: %s needs a value\n", a); return 2; }
        if (!strcmp(a, "--size") && !parse_size(v, &tw, &th)) ++i;
        else if (!strcmp(a, "--error-size") && !parse_size(v, &ew, &eh)) ++i;
        else if (!strcmp(a, "--error-render") && !parse_size(v, &rw, &rh)) ++i;
        else if (!strcmp(a, "--cost") && (!strcmp(v, "gpu") || !strcmp(v, "cpu"))) cost_cpu = !strcmp(v, "cpu"), ++i;
        else if (!strcmp(a, "--frames") && (frames = atoi(v)) > 0) ++i;
        else if (!strcmp(a, "--csv")) csv = v, ++i;
        else if (!strcmp(a, "--emit-table")) table = v, ++i;
        else if (!strcmp(a, "--configs")) configs = v, ++i;
        else if (!strcmp(a, "--scenes")) scenes = v, ++i;
        else if (!strcmp(a, "--device")) device = atoi(v), ++i;
        else if (!strcmp(a, "--horizon-size") && !parse_size(v, &hw, &hh)) ++i;
        else if (!strcmp(a, "--emit-horizon-table")) horizon_table = v, ++i;
        else if (!strcmp(a, "--horizon-reference") && quality_preset(v)) horizon_ref = quality_preset(v), ++i;
        else if (!strcmp(a, "--sun-visibility") && (!strcmp(v, "penumbra") || !strcmp(v, "lesson-fade")))
            lesson = !strcmp(v, "lesson-fade"), ++i;
        else { fprintf(stderr, "tradeoff: bad argument %s %s\n", a, v); return 2; }
    }
    gpu_context ctx;
    gpu_context_desc desc = {.device_index = device, .validation = validate};
    if (gpu_context_create(&ctx, &desc) != 0) return 1;
    if (rw == 0) rw = ew, rh = eh;
    if (rw < ew || rh < eh) { fprintf(stderr, "tradeoff: --error-render %dx%d is smaller than the %dx%d grid\n", rw, rh, ew, eh); return 2; }
    error_grid grid = {.w = ew, .h = eh, .full_w = rw, .full_h = rh};
    fprintf(stderr, "tradeoff: device %s, timing at %dx%d (%d frames), error at a %dx%d grid of %dx%d frames\n",
            ctx.props.deviceName, tw, th, frames, ew, eh, rw, rh);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    if (lesson) a.sun_visibility = MODEL_SUN_VISIBILITY_LESSON_FADE;
    int nconf = 4 + quality_sweep_count;
    if (horizon_table) return emit_horizon_table(&ctx, horizon_table, configs, scenes, hw, hh, &a, horizon_ref);
    row *rows = calloc((size_t)nconf * QUALITY_SCENE_COUNT, sizeof *rows);
    int count = 0;
    float *refs[QUALITY_SCENE_COUNT];
    unsigned char *masks[QUALITY_SCENE_COUNT];
    for (int s = 0; s < QUALITY_SCENE_COUNT; ++s) {
        refs[s] = NULL, masks[s] = NULL;
        if (!wanted(scenes, quality_scenes[s].name)) continue;
        refs[s] = reference_image(&a, &quality_scenes[s], &grid);
        masks[s] = malloc((size_t)ew * eh);
        error_mask(&a, &quality_scenes[s], &grid, masks[s]);
    }
    FILE *out = fopen(csv, "w");
    if (!out) { fprintf(stderr, "tradeoff: cannot write %s\n", csv); return 1; }
    fprintf(out, "device,config,scene,width,height,sky_gpu_ms,frame_gpu_ms,wall_ms,err_mean,err_p95,err_max,ciede2000,cpu_ms,"
                 "horizon_max,horizon_mean,color_de_spectral\n");
    float *horizon_refs[QUALITY_SCENE_COUNT] = {0};
    for (int c = 0; c < nconf; ++c) {
        const quality_config *q = c < 4 ? &quality_presets[c] : &quality_sweep[c - 4];
        if (!wanted(configs, q->name)) continue;
        for (int s = 0; s < QUALITY_SCENE_COUNT; ++s) {
            if (!refs[s]) continue;
            row *r = &rows[count++];
            r->config = q->name;
            r->scene = s;
            measure_time(&ctx, q, &quality_scenes[s], tw, th, frames, &a, r);
            /* The fill floor has no accuracy to speak of. */
            if (q->mode == SKY_CHOICE_FILL) r->err.mean = r->err.p95 = r->err.max = r->de2000 = NAN;
            else measure_error(&ctx, q, &quality_scenes[s], &grid, &a, refs[s], masks[s], r);
            r->horizon.max = r->horizon.mean = NAN;
            if (q->mode != SKY_CHOICE_FILL) {
                if (!horizon_refs[s])
                    horizon_refs[s] = horizon_frame(&ctx, horizon_ref, &quality_scenes[s], hw, hh, &a, SUN_RADIUS);
                float *lum = horizon_frame(&ctx, q, &quality_scenes[s], hw, hh, &a, SUN_RADIUS);
                r->horizon = horizon_band_error(lum, horizon_refs[s], &quality_scenes[s], hw, hh, &a, SUN_RADIUS);
                free(lum);
            }
            /* The colour axis (issue 32): every configuration renders RGB, whose worst CIEDE2000 against the
             * 48-wavelength spectral reference on this class is measured once (quality_color_table.h); ciede2000 above
             * is the numerics' error against the RGB reference. */
            fprintf(out, "\"%s\",%s,%s,%d,%d,%.4f,%.4f,%.4f,%.5f,%.5f,%.5f,%.4f,%.4f,%.5f,%.5f,%.2f\n", ctx.props.deviceName,
                    q->name, quality_scenes[s].name, tw, th, r->sky_ms, r->frame_ms, r->wall_ms, r->err.mean, r->err.p95,
                    r->err.max, r->de2000, r->cpu_ms, r->horizon.max, r->horizon.mean, quality_color_error(0, s));
            fflush(out);
            fprintf(stderr, "%-20s %-13s sky %8.3f ms frame %8.3f ms wall %8.2f ms cpu %8.2f ms | err mean %6.2f%% p95 %6.2f%% max %6.2f%% dE00 %.2f\n",
                    q->name, quality_scenes[s].name, r->sky_ms, r->frame_ms, r->wall_ms, r->cpu_ms, 100 * r->err.mean,
                    100 * r->err.p95, 100 * r->err.max, r->de2000);
        }
    }
    fclose(out);
    print_color_axis(refs);
    if (table) {
        FILE *t = fopen(table, "w");
        if (t) {
            /* The GPU table declares the row type; the CPU table (quality_table_cpu.h) reuses it. */
            const char *name = cost_cpu ? "quality_table_cpu" : "quality_table";
            fprintf(t, "/* Measured by tools/tradeoff on %s (%s at %dx%d, median of %d frames; mean relative\n"
                       " * luminance error at a %dx%d grid of %dx%d frames vs the converged reference).\n"
                       " * Regenerate: tradeoff%s --emit-table FILE. */\n",
                    ctx.props.deviceName, cost_cpu ? "process CPU ms per whole frame, bloom and tone map included"
                                                   : "sky GPU ms", tw, th, frames, ew, eh, rw, rh,
                    cost_cpu ? " --cost cpu" : "");
            /* The key of what was measured (issue 31): a build with other shaders or knobs sees its rows as estimates. */
            const char *names[512];
            int named = 0;
            for (int i = 0; i < count && named < 512; ++i)
                if (isfinite(rows[i].err.mean)) names[named++] = rows[i].config;
            char key[96];
            quality_names_key(names, named, key, sizeof key);
            fprintf(t, "#define %s \"%s\"\n", cost_cpu ? "QUALITY_TABLE_CPU_KEY" : "QUALITY_TABLE_KEY", key);
            if (!cost_cpu)
                fprintf(t, "typedef struct quality_measurement { const char *config; int scene; double gpu_ms, err_mean, err_p95; } quality_measurement;\n");
            fprintf(t, "static const quality_measurement %s[] = {\n", name);
            for (int i = 0; i < count; ++i)
                if (isfinite(rows[i].err.mean))
                    fprintf(t, "    {\"%s\", %d, %.4f, %.5f, %.5f},\n", rows[i].config, rows[i].scene,
                            cost_cpu ? rows[i].cpu_ms : rows[i].sky_ms, rows[i].err.mean, rows[i].err.p95);
            /* The count from the array itself: a row added or removed by hand (a re-measured class) keeps it true. */
            fprintf(t, "};\nstatic const int %s_count = (int)(sizeof %s / sizeof %s[0]);\n", name, name, name);
            fclose(t);
        }
    }
    gpu_context_destroy(&ctx);
    return 0;
}
