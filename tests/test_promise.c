/* The promise tested (issue 31 item 1): on the device this test runs on, the configuration --quality auto and
 * --max-error 0.005 / 0.01 / 0.02 pick for each scene class (quality_auto, quality_pick with the running device's
 * kind: the functions options.c calls) is rendered, measured against the converged CPU reference, and held to
 * what the pick promises: --max-error E: a mean relative luminance error <= E; auto: <= its stated bound,
 * max(QUALITY_AUTO_FLOOR, QUALITY_AUTO_SLACK x the best error the table measured on the class).
 *
 * The measurement is the test's own: the pixel directions and the radiance are the CPU reference's (ref_pixel_dir,
 * ref_sky_radiance at ref_quality_converged), the sky mask (rays that miss the planet, with their four neighbours,
 * and nothing within 4 sun radii of the sun) and the metric (|L - Lref| / max(Lref, 1e-3 x the brightest Lref),
 * Rec.709 luminance) are written here, not taken from reference/metrics.c nor tools/tradeoff.
 * The frame is 640x360 (the tables measured 1280x720 on the CPU device and 1920x1080 / 96x54 on the GPU) sampled
 * at a 48x27 grid of its pixels: a configuration's error grows a little as the frame shrinks (its sky-view LUT and
 * render scale are fixed), so the promise is held here at a smaller frame than the table's and a pass is not
 * borrowed from size. VKSKY_PROMISE_SIZE=WxH overrides the frame (a documented run at the table's size),
 * VKSKY_PROMISE_SCENES=a,b runs some classes only. On the table's own device kind each quoted row is also compared
 * with the measurement (check_row), so a table gone stale fails. */
#include "app/quality/quality.h"
#include "app/quality/quality_table.h"
#include "app/quality/quality_table_cpu.h"
#include "gpu_test.h"

enum { GRID_W = 48, GRID_H = 27 };
static int frame_w = 640, frame_h = 360;

static int grid_x(int i) { return (int)(((double)i + 0.5) * frame_w / GRID_W); }
static int grid_y(int j) { return (int)(((double)j + 0.5) * frame_h / GRID_H); }

/* Does the ray from the camera at altitude h along d hit the planet? (d.y is up; written here, not metrics.c's.) */
static bool hits_ground(double radius, double h, const double d[3])
{
    double r = radius + h;   /* camera at (0, r, 0) */
    double b = r * d[1];
    double c = h * (2.0 * radius + h);   /* r^2 - R^2 without cancellation */
    return b < 0.0 && b * b - c >= 0.0;
}

/* The reference at the grid, the mask, and the floor of the metric, for one scene. */
typedef struct scene_ref {
    float lum[GRID_W * GRID_H];
    unsigned char mask[GRID_W * GRID_H];
    double floor_lum;
    int count;
} scene_ref;

static void reference_of(const model_atmosphere *a, const quality_scene *s, scene_ref *out)
{
    double sun[3];
    ref_dir(0.0, s->sun_elevation_deg * TEST_DEG, sun);
    double cos_sun = cos(4.0 * SUN_RADIUS_RAD), brightest = 0.0;
    out->count = 0;
    for (int j = 0; j < GRID_H; ++j)
        for (int i = 0; i < GRID_W; ++i) {
            int k = j * GRID_W + i, px = grid_x(i), py = grid_y(j);
            bool sky = true;
            const int nx[5] = {0, 1, -1, 0, 0}, ny[5] = {0, 0, 0, 1, -1};
            double d[3];
            for (int n = 4; n >= 0; --n) {   /* n = 0 last: d is the pixel's own direction */
                ref_pixel_dir(px + nx[n], py + ny[n], frame_w, frame_h, s->yaw_deg * TEST_DEG, s->pitch_deg * TEST_DEG,
                              s->fov_deg * TEST_DEG, d);
                sky = sky && !hits_ground(a->bottom_radius, s->altitude_km, d);
            }
            if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > cos_sun) sky = false;
            out->mask[k] = sky;
            out->lum[k] = 0.0f;
            if (!sky) continue;
            double rgb[3];
            ref_sky_radiance(a, s->altitude_km, d, sun, ref_quality_converged(), rgb);
            out->lum[k] = (float)(0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]);
            brightest = fmax(brightest, out->lum[k]);
            ++out->count;
        }
    out->floor_lum = 1e-3 * brightest;
}

static double mean_error(const test_frame *f, const scene_ref *r)
{
    double sum = 0.0;
    for (int j = 0; j < GRID_H; ++j)
        for (int i = 0; i < GRID_W; ++i) {
            int k = j * GRID_W + i;
            if (!r->mask[k]) continue;
            double l = luminance(test_pixel(f, grid_x(i), grid_y(j)));
            sum += fabs(l - r->lum[k]) / fmax(r->lum[k], r->floor_lum);
        }
    return r->count ? sum / r->count : INFINITY;
}

/* One configuration on one scene: rendered once, whoever picked it. */
typedef struct measured { const quality_config *q; int scene; double err; } measured;
static measured cache[64];
static int cache_count;

/* A stale table fails (issue 31): on the device kind a table was measured on, the row the pick quotes must agree
 * with this measurement within max(0.1 point, 15 %) — the grids (48x27 of 640x360 here, 96x54 of 1280x720 there)
 * differ, nothing else. Not at the 400 km limb, where a render-scale-0.5 configuration's error depends on the
 * frame's size (docs/horizon.md), nor on a GPU: the GPU table measured 96x54 frames (docs/claims.md). */
static void check_row(bool cpu_device, int scene, const char *what, const char *config, double measured, double table)
{
    if (!cpu_device || scene == 5) return;
    CHECK(fabs(measured - table) <= fmax(0.001, 0.15 * table), "%s on %s: '%s' measured %.4f, the table says %.4f: "
          "the table is stale (re-measure: tools/tradeoff)", what, quality_scenes[scene].name, config, measured, table);
}

static double error_of(gpu_context *ctx, const model_atmosphere *a, const quality_config *q, int scene,
                       const scene_ref *r)
{
    for (int i = 0; i < cache_count; ++i)
        if (cache[i].q == q && cache[i].scene == scene) return cache[i].err;
    sky_view v = quality_scene_view(&quality_scenes[scene]);
    v.bloom = false;   /* the promise is the sky's radiance; bloom is an effect on top, off in the tables too */
    sky_renderer_desc desc = {.width = (uint32_t)frame_w, .height = (uint32_t)frame_h, .bloom = false,
                              .readback = true, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    desc.lut = sky_lut_quality_default();
    int bloom_mips = 5;
    quality_apply(q, &v, &desc.lut, &desc.render_scale, &bloom_mips, &desc.bloom_quarter);
    desc.bloom_mips = (uint32_t)bloom_mips;
    test_renderer t = {.width = frame_w, .height = frame_h};
    sky_renderer_create(&t.r, ctx, &desc);
    sky_renderer_set_atmosphere(&t.r, a, SUN_RADIUS_RAD);
    test_frame f = test_renderer_frame(&t, &v);
    double err = mean_error(&f, r);
    CHECK(count_bad_pixels(&f) == 0, "%s on %s: non-finite or negative pixels", q->name, quality_scenes[scene].name);
    test_frame_free(&f);
    test_renderer_destroy(&t);
    if (cache_count < 64) cache[cache_count++] = (measured){q, scene, err};
    return err;
}

int main(void)
{
    const char *size = getenv("VKSKY_PROMISE_SIZE");
    if (size && *size && (sscanf(size, "%dx%d", &frame_w, &frame_h) != 2 || frame_w < GRID_W || frame_h < GRID_H)) {
        fprintf(stderr, "test_promise: VKSKY_PROMISE_SIZE '%s': expected WxH of at least %dx%d\n", size, GRID_W, GRID_H);
        return 2;
    }
    gpu_context ctx;
    test_context(&ctx);
    bool cpu_device = ctx.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    printf("device: %s (%s table), frame %dx%d, grid %dx%d\n", ctx.props.deviceName, cpu_device ? "CPU" : "GPU",
           frame_w, frame_h, GRID_W, GRID_H);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    static const double budgets[] = {0.005, 0.01, 0.02};
    const char *only = getenv("VKSKY_PROMISE_SCENES");   /* a documented run of some classes: "400km-limb,noon" */
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c) {
        const quality_scene *s = &quality_scenes[c];
        if (only && *only && !strstr(only, s->name)) continue;
        unsigned classes = quality_class_bit(s->altitude_km, s->sun_elevation_deg);
        CHECK(classes == 1u << c, "scene %s is not its own class", s->name);
        static scene_ref r;
        reference_of(&a, s, &r);
        CHECK(r.count > GRID_W * GRID_H / 4, "%s: only %d sky samples", s->name, r.count);
        double quoted = 0.0;
        const quality_config *q = quality_auto(classes, cpu_device, &quoted);
        CHECK(q != NULL, "auto picked nothing on %s", s->name);
        if (q) {
            /* The stated bound (quality.h): from the best row the device's table measured on the class. */
            const quality_measurement *table = cpu_device ? quality_table_cpu : quality_table;
            int count = cpu_device ? quality_table_cpu_count : quality_table_count;
            double best = INFINITY;
            for (int i = 0; i < count; ++i)
                if (table[i].scene == c) best = fmin(best, table[i].err_mean);
            double bound = fmax(QUALITY_AUTO_FLOOR, QUALITY_AUTO_SLACK * best);
            double err = error_of(&ctx, &a, q, c, &r);
            printf("%-13s auto           -> %-38s measured %.4f (table %.4f), bound %.4f\n", s->name, q->name, err,
                   quoted, bound);
            CHECK(err <= bound, "auto on %s: '%s' measured %.4f over its bound %.4f", s->name, q->name, err, bound);
            check_row(cpu_device, c, "auto", q->name, err, quoted);
        }
        for (size_t b = 0; b < sizeof budgets / sizeof budgets[0]; ++b) {
            double table_err = 0.0;
            const quality_config *p = quality_pick(budgets[b], classes, cpu_device, &table_err);
            if (!p) {   /* refused: the CLI says so (exit 2); nothing promised */
                printf("%-13s --max-error %.3f -> none measured within\n", s->name, budgets[b]);
                continue;
            }
            double err = error_of(&ctx, &a, p, c, &r);
            printf("%-13s --max-error %.3f -> %-38s measured %.4f (table %.4f)\n", s->name, budgets[b], p->name, err,
                   table_err);
            CHECK(err <= budgets[b], "--max-error %g on %s: '%s' measured %.4f", budgets[b], s->name, p->name, err);
            check_row(cpu_device, c, "--max-error", p->name, err, table_err);
        }
    }
    gpu_context_destroy(&ctx);
    return test_finish("test_promise");
}
