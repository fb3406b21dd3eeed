/* Lit ground, the ground-irradiance LUT and the ground bounce against the path tracer (issue 31 item 2).
 * The GPU with ground albedo 0.3 (the lit-ground variant: the ground-irradiance LUT, the ground's bounce in the
 * multi-scattering LUT), --quality ultra's LUTs and march, against pt_radiance with a Lambertian ground of albedo
 * 0.3 (all orders, true phase functions; src/reference/path_tracer.c shares no code with the shaders). The CPU
 * reference models albedo 0 only, so the path tracer is the only independent answer here.
 * Views (sun 30 deg): the ground 30 deg down from 1 m (its radiance: the sun's and the sky's irradiance),
 * the ground 20 deg down from 10 km (lit ground through 29 km of air), the sky 10 deg up away from the sun from 1 m
 * (the ground's bounce is part of its light). Bound: the daytime target of the model (3 %, docs/model_error.md) plus
 * 3 standard errors of the tracer's estimate. And the ground's share: the sky 10 deg up gains light from the lit
 * ground by as much as the tracer says (the albedo-0.3 minus albedo-0 difference, below).
 * The ground's bounce into the sky (issue 31f): the multi-scattering LUT's ground is lit by the sun and the sky (a
 * second multi-scattering pass reads the ground-irradiance LUT made from the first; docs/model.md "Lit ground").
 * Before that its ground was lit by the sun alone, as in Hillaire 2020, and the bounce was 18 % low (GPU +0.150,
 * tracer +0.182): 13 % of the ground's light comes from the sky (luminance; R 6 %, G 14 %, B 30 %). The bounce is
 * asserted against the tracer's whole bounce within the model's documented error of the second bounce's angular
 * model (5 %: -3.4 % measured against the tracer's sunlit-only bounce, -2.6 % with 4x the paths; docs/claims.md) +
 * 3 standard errors; the tracer's bounce from the sunlit part of the ground alone is printed as a diagnostic.
 * ~110 s of CPU on lavapipe (553 s of wall on a loaded 2-core machine). */
#include "app/quality/quality.h"
#include "gpu_test.h"
#include "reference/path_tracer.h"

enum { N = 17 };

typedef struct view_case { const char *name; double altitude, yaw, pitch; long long samples; } view_case;

/* A renderer with ultra's LUTs and the lit-ground variant at one albedo: its LUTs are built once, for every view. */
static void renderer_for(sky_renderer *r, gpu_context *ctx, const model_atmosphere *a, double albedo, sky_view *v)
{
    *v = sky_view_default();
    sky_renderer_desc desc = {.width = N, .height = N, .readback = true, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    desc.lut = sky_lut_quality_default();
    int bloom_mips = 5;
    quality_apply(quality_preset("ultra"), v, &desc.lut, &desc.render_scale, &bloom_mips, &desc.bloom_quarter);
    desc.bloom_mips = (uint32_t)bloom_mips;
    sky_renderer_create(r, ctx, &desc);
    sky_renderer_set_atmosphere(r, a, SUN_RADIUS_RAD);
    sky_features f = sky_features_default();
    f.ground_albedo[0] = f.ground_albedo[1] = f.ground_albedo[2] = albedo;
    f.sun_disc = false;
    sky_renderer_set_features(r, &f);
}

static void gpu_centre(sky_renderer *r, sky_view v, const view_case *c, double out[3])
{
    v.altitude_km = c->altitude, v.sun_elevation_deg = 30.0, v.sun_azimuth_deg = 0.0;
    v.yaw_deg = c->yaw, v.pitch_deg = c->pitch, v.fov_deg = 2.0, v.bloom = false;
    frame_desc fd = {.view = &v};
    sky_renderer_render(r, &fd);
    const uint16_t *half = r->readback_linear.mapped;
    for (int k = 0; k < 3; ++k) out[k] = io_half_to_float(half[4 * ((N / 2) * N + N / 2) + k]);
}

static double lum3(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static double lum3_se(const double e[3])
{
    return sqrt(0.2126 * 0.2126 * e[0] * e[0] + 0.7152 * 0.7152 * e[1] * e[1] + 0.0722 * 0.0722 * e[2] * e[2]);
}

/* The tracer's radiance (RGB and its standard errors) and its luminance with its standard error. */
static void traced(const model_atmosphere *a, double albedo, const view_case *c, double rgb[3], double err[3],
                   double *L, double *se)
{
    double v[3], s[3];
    ref_dir(c->yaw * TEST_DEG, c->pitch * TEST_DEG, v);
    ref_dir(0.0, 30.0 * TEST_DEG, s);
    pt_settings ps = {c->samples, 3131ull, albedo, 0, 2};
    pt_radiance(a, c->altitude, v, s, &ps, rgb, err);
    *L = lum3(rgb);
    *se = lum3_se(err);
}

int main(void)
{
    gpu_context ctx;
    test_context(&ctx);
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    const view_case cases[] = {
        {"ground 30 deg down, 1 m", 0.001, 180.0, -30.0, 20000},
        {"ground 20 deg down, 10 km", 10.0, 90.0, -20.0, 20000},
        {"sky 10 deg up, away, 1 m", 0.001, 180.0, 10.0, 40000},
    };
    sky_renderer lit, dark;
    sky_view lit_view, dark_view;
    renderer_for(&lit, &ctx, &earth, 0.3, &lit_view);
    renderer_for(&dark, &ctx, &earth, 0.0, &dark_view);
    /* The ground's direct share (ground 30 deg down from 1 m, case 0): the sun's term 0.3/pi E T(0, mu 0.5) 0.5 in
     * closed form (the transmittance from the reference's fine march), over the tracer's whole ground radiance (the
     * sun's and the sky's light; the 2 m of air in front of it add < 0.1 %). */
    double direct_share[3] = {0};
    for (int i = 0; i < 3; ++i) {
        const view_case *c = &cases[i];
        double g[3], g0[3], Lp, sp, Lp0, sp0, p_rgb[3], p_err[3], p0_rgb[3], p0_err[3];
        gpu_centre(&lit, lit_view, c, g);
        traced(&earth, 0.3, c, p_rgb, p_err, &Lp, &sp);
        if (i == 0) {
            double T[3];
            ref_transmittance(&earth, 0.0, 0.5, 2000, T);
            for (int k = 0; k < 3; ++k) direct_share[k] = 0.3 / (180.0 * TEST_DEG) * earth.sun_illuminance[k] * T[k] * 0.5 / p_rgb[k];
            printf("the ground's light from the sky (tracer): %.1f %% (R %.1f, G %.1f, B %.1f %%)\n",
                   100.0 * (1.0 - lum3((double[3]){direct_share[0] * p_rgb[0], direct_share[1] * p_rgb[1],
                                                   direct_share[2] * p_rgb[2]}) / Lp),
                   100.0 * (1.0 - direct_share[0]), 100.0 * (1.0 - direct_share[1]), 100.0 * (1.0 - direct_share[2]));
        }
        double Lg = lum3(g), err = Lg / Lp - 1.0, bound = 0.03 + 3.0 * sp / Lp;
        printf("%-28s GPU %.5g  PT %.5g +- %.2g  error %+.2f %% (bound %.2f %%)\n", c->name, Lg, Lp, sp, 100 * err,
               100 * bound);
        CHECK(fabs(err) <= bound, "%s: GPU %.5g vs path tracer %.5g (albedo 0.3): %+.2f %% over %.2f %%", c->name, Lg, Lp,
              100 * err, 100 * bound);
        if (c->pitch > 0.0) {   /* the sky: what the lit ground adds, GPU against tracer */
            gpu_centre(&dark, dark_view, c, g0);
            traced(&earth, 0.0, c, p0_rgb, p0_err, &Lp0, &sp0);
            double dg = Lg - lum3(g0), dp = Lp - Lp0, dse = sqrt(sp * sp + sp0 * sp0);
            printf("%-28s ground bounce: GPU +%.4g, PT +%.4g +- %.2g (GPU %+.1f %%)\n", c->name, dg, dp, dse,
                   100.0 * (dg / dp - 1.0));
            CHECK(dp > 3.0 * dse, "%s: the tracer sees no ground bounce (%.4g +- %.2g): the case cannot test it", c->name,
                  dp, dse);
            /* The whole bounce (the ground lit by the sun and the sky) within the second bounce's angular model (5 %)
             * + 3 standard errors. The ground lit by the sun alone (Hillaire's term; 13 % low in the ground's light)
             * fails it, as do a lost, doubled or mis-normalised ground term. */
            CHECK(fabs(dg - dp) <= 0.05 * dp + 3.0 * dse, "%s: ground bounce GPU %.4g vs path tracer %.4g +- %.2g",
                  c->name, dg, dp, dse);
            /* Diagnostic: the tracer's bounce channel by channel times the ground's direct share is the bounce of
             * the sunlit part of the ground alone (what a multi-scattering LUT with Hillaire's ground term gives). */
            double dp_sun[3], dse_sun[3];
            for (int k = 0; k < 3; ++k) {
                dp_sun[k] = (p_rgb[k] - p0_rgb[k]) * direct_share[k];
                dse_sun[k] = sqrt(p_err[k] * p_err[k] + p0_err[k] * p0_err[k]) * direct_share[k];
            }
            printf("%-28s the tracer's bounce from the sunlit part of the ground alone: +%.4g +- %.2g (GPU %+.1f %%)\n",
                   c->name, lum3(dp_sun), lum3_se(dse_sun), 100.0 * (dg / lum3(dp_sun) - 1.0));
        }
    }
    sky_renderer_destroy(&lit);
    sky_renderer_destroy(&dark);
    gpu_context_destroy(&ctx);
    return test_finish("test_ground_pt");
}
