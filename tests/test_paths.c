/* The fast paths agree with the per-pixel fragment march on the trade-off scene set (issue 5):
 *  - the compute sky pass computes the same function: within fp16 rounding (relative 2e-3 per pixel);
 *  - the sky-view LUT lookup (192x108, 30 steps) approximates the march: mean relative luminance difference
 *    <= 1 % and p95 <= 3 % over sky pixels on the daytime scenes (its own error vs the reference is measured
 *    by tools/tradeoff and listed in the README);
 *  - every preset renders, finite.
 * Validation + synchronization validation on; any message fails. */
#include "app/quality/quality.h"
#include "gpu_test.h"
#include "reference/metrics.h"
#include <string.h>

enum { W = 96, H = 54 };

/* The march and sky-view frames (no preset): one renderer for all of them, since they share the default LUTs and
 * Earth and differ only in the view (mode, pass kind, camera, sun), which every frame takes afresh (its sky-view LUT
 * too); a renderer per frame computed the same LUTs 24 times. */
static test_renderer plain;

static test_frame render_with(gpu_context *ctx, const quality_scene *s, sky_mode_choice mode, sky_pass_kind kind,
                              const quality_config *preset)
{
    sky_view v = sky_view_default();
    v.altitude_km = s->altitude_km;
    v.sun_elevation_deg = s->sun_elevation_deg;
    v.yaw_deg = s->yaw_deg;
    v.pitch_deg = s->pitch_deg;
    v.fov_deg = s->fov_deg;
    v.bloom = false;
    sky_lut_quality lut = sky_lut_quality_default();
    if (preset) {
        double scale;
        int mips;
        bool quarter;
        quality_apply(preset, &v, &lut, &scale, &mips, &quarter);
        v.bloom = true;
    } else {
        v.mode = mode;
        v.pass_kind = kind;
        return test_renderer_frame(&plain, &v);
    }
    return test_render_quality(ctx, &v, W, H, &lut);
}

int main(void)
{
    gpu_context ctx;
    test_context(&ctx);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    unsigned char mask[W * H];
    test_renderer_create(&plain, &ctx, W, H, false, NULL, NULL);
    for (int i = 0; i < 6; ++i) {
        const quality_scene *s = &quality_scenes[i];
        test_frame frag = render_with(&ctx, s, SKY_CHOICE_MARCH, SKY_PASS_FRAGMENT, NULL);
        test_frame comp = render_with(&ctx, s, SKY_CHOICE_MARCH, SKY_PASS_COMPUTE, NULL);
        test_frame view = render_with(&ctx, s, SKY_CHOICE_SKYVIEW, SKY_PASS_FRAGMENT, NULL);
        test_frame view_comp = render_with(&ctx, s, SKY_CHOICE_SKYVIEW, SKY_PASS_COMPUTE, NULL);
        CHECK(count_bad_pixels(&frag) + count_bad_pixels(&comp) + count_bad_pixels(&view) == 0, "%s: bad pixels", s->name);
        /* Compute vs fragment: the same function, so per pixel within fp16 rounding. */
        double worst = 0.0;
        for (int p = 0; p < W * H * 4; ++p) {
            if (p % 4 == 3) continue;
            double d = fabs(frag.linear[p] - comp.linear[p]) / fmax(fabs(frag.linear[p]), 1e-6);
            if (d > worst) worst = d;
            d = fabs(view.linear[p] - view_comp.linear[p]) / fmax(fabs(view.linear[p]), 1e-6);
            if (d > worst) worst = d;
        }
        printf("%-13s compute vs fragment: max relative difference %.2e\n", s->name, worst);
        CHECK(worst <= 2e-3, "%s: compute and fragment sky passes differ by %.2e", s->name, worst);
        /* Sky-view lookup vs the march (camera inside the atmosphere only: from space auto uses the march). */
        if (s->altitude_km < 100.0) {
            metrics_sky_mask(&a, s->altitude_km, W, H, s->yaw_deg * TEST_DEG, s->pitch_deg * TEST_DEG,
                             s->fov_deg * TEST_DEG, mask);
            double max_lum = 0.0;
            for (int p = 0; p < W * H; ++p)
                if (mask[p]) max_lum = fmax(max_lum, luminance(&frag.linear[4 * p]));
            /* Exclude the sun's disc: both paths draw it, but the lookup path's transmittance comes from the LUT. */
            double sun[3];
            ref_dir(0.0, s->sun_elevation_deg * TEST_DEG, sun);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    double d[3];
                    ref_pixel_dir(x, y, W, H, s->yaw_deg * TEST_DEG, s->pitch_deg * TEST_DEG, s->fov_deg * TEST_DEG, d);
                    if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > cos(4.0 * SUN_RADIUS_RAD)) mask[y * W + x] = 0;
                }
            metrics_luminance m = metrics_relative_luminance(view.linear, frag.linear, mask, W, H, 1e-3 * max_lum);
            printf("%-13s sky-view vs march: mean %.2f%% p95 %.2f%% max %.2f%% (%d sky pixels)\n", s->name, 100 * m.mean,
                   100 * m.p95, 100 * m.max, m.count);
            bool daytime = s->sun_elevation_deg > 0.0;
            if (daytime) {
                CHECK(m.mean <= 0.01 && m.p95 <= 0.03, "%s: sky-view path differs from the march: mean %.2f%% p95 %.2f%%",
                      s->name, 100 * m.mean, 100 * m.p95);
            }
        }
        test_frame_free(&frag), test_frame_free(&comp), test_frame_free(&view), test_frame_free(&view_comp);
    }
    test_renderer_destroy(&plain);
    /* Every preset renders (bloom on), finite and non-negative. */
    for (int i = 0; i < 4; ++i) {
        test_frame f = render_with(&ctx, &quality_scenes[1], SKY_CHOICE_AUTO, SKY_PASS_AUTO, &quality_presets[i]);
        CHECK(count_bad_pixels(&f) == 0, "preset %s: bad pixels", quality_presets[i].name);
        printf("preset %-6s renders\n", quality_presets[i].name);
        test_frame_free(&f);
    }
    gpu_context_destroy(&ctx);
    return test_finish("test_paths");
}
