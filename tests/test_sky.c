/* Rendered frames checked on pixels whose view direction the test computes (odd sizes put the centre pixel
 * exactly on the view axis): physics (blue noon zenith, red sunset horizon, dark twilight, the sun disc and
 * its occlusion), finiteness of every output pixel, and agreement with the CPU reference. */
#include "gpu_test.h"
#include "test_atmospheres.h"
#include <string.h>

enum { N = 33, C = N / 2 };

static int frames_rendered;

/* Renders a 33x33 frame looking along (yaw, pitch) and returns the centre pixel; checks every pixel. */
static void probe(gpu_context *ctx, sky_view v, double yaw, double pitch, float out[3])
{
    v.yaw_deg = yaw;
    v.pitch_deg = pitch;
    test_frame f = test_render(ctx, &v, N, N);
    int bad = count_bad_pixels(&f);
    CHECK(bad == 0, "%d NaN/Inf/negative values (sun el %.2f, yaw %.1f, pitch %.1f)", bad, v.sun_elevation_deg, yaw, pitch);
    const float *p = test_pixel(&f, C, C);
    memcpy(out, p, 3 * sizeof(float));
    ++frames_rendered;
    test_frame_free(&f);
}

static sky_view scene(double sun_elevation, bool bloom)
{
    sky_view v = sky_view_default();
    v.sun_azimuth_deg = 30.0;
    v.sun_elevation_deg = sun_elevation;
    v.altitude_km = 0.001;
    v.fov_deg = 20.0;
    v.bloom = bloom;
    return v;
}

static double rel_err(double gpu, double ref) { return fabs(gpu - ref) / fmax(ref, 1e-9); }

typedef struct view_case { double sun_el, yaw, pitch; } view_case;

/* Renders view case k with renderer t (of atmosphere `a`, NULL: Earth) and returns the centre pixel in gpu and
 * the luminance error against the converged CPU reference; prints a line tagged `tag`. steps 0: the default. */
static double versus_reference(test_renderer *t, const char *tag, view_case k, int steps, const model_atmosphere *a,
                               float gpu[3])
{
    sky_view v = scene(k.sun_el, false);
    v.yaw_deg = k.yaw;
    v.pitch_deg = k.pitch;
    if (steps) v.steps = steps;
    test_frame f = test_renderer_frame(t, &v);
    CHECK(count_bad_pixels(&f) == 0, "NaN/Inf/negative pixels (%s)", tag);
    memcpy(gpu, test_pixel(&f, C, C), 3 * sizeof(float));
    test_frame_free(&f);
    ++frames_rendered;
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    double view_dir[3], sun_dir[3], ref[3];
    ref_dir(k.yaw * TEST_DEG, k.pitch * TEST_DEG, view_dir);
    ref_dir(v.sun_azimuth_deg * TEST_DEG, v.sun_elevation_deg * TEST_DEG, sun_dir);
    ref_sky_radiance(a ? a : &earth, v.altitude_km, view_dir, sun_dir, ref_quality_converged(), ref);
    double e = rel_err(luminance(gpu), 0.2126 * ref[0] + 0.7152 * ref[1] + 0.0722 * ref[2]);
    printf("%-9s sun %5.1f view (%5.1f, %5.1f): gpu %.5f %.5f %.5f ref %.5f %.5f %.5f  luminance error %.2f%%\n", tag,
           k.sun_el, k.yaw, k.pitch, gpu[0], gpu[1], gpu[2], ref[0], ref[1], ref[2], 100 * e);
    return e;
}

int main(void)
{
    gpu_context ctx;
    test_context(&ctx);
    float noon_zenith[3], sunset_zenith[3], sunset_horizon[3], twilight_zenith[3], disc[3], beside[3], hidden[3];

    /* Noon: the zenith is blue, B > G > R. */
    probe(&ctx, scene(70.0, true), 0.0, 90.0, noon_zenith);
    printf("noon zenith      %.4f %.4f %.4f\n", noon_zenith[0], noon_zenith[1], noon_zenith[2]);
    CHECK(noon_zenith[2] > noon_zenith[1] && noon_zenith[1] > noon_zenith[0], "noon zenith not blue");

    /* Sunset (sun 2 deg): the horizon toward the sun is redder than the zenith. */
    probe(&ctx, scene(2.0, true), 0.0, 90.0, sunset_zenith);
    probe(&ctx, scene(2.0, true), 30.0, 1.0, sunset_horizon);
    double rb_zenith = sunset_zenith[0] / sunset_zenith[2], rb_horizon = sunset_horizon[0] / sunset_horizon[2];
    printf("sunset R/B: zenith %.3f horizon toward the sun %.3f\n", rb_zenith, rb_horizon);
    CHECK(rb_horizon > 2.0 * rb_zenith, "sunset horizon R/B %.3f not well above the zenith's %.3f", rb_horizon, rb_zenith);
    CHECK(rb_horizon > 1.0, "sunset horizon toward the sun is not red (R/B %.3f)", rb_horizon);

    /* Twilight (sun -6 deg): at least 10x darker than noon. */
    probe(&ctx, scene(-6.0, true), 0.0, 90.0, twilight_zenith);
    double ratio = luminance(noon_zenith) / fmax(luminance(twilight_zenith), 1e-12);
    printf("noon / twilight zenith luminance: %.1f\n", ratio);
    CHECK(ratio >= 10.0, "twilight only %.1fx darker than noon", ratio);

    /* The sun disc: present at noon (far brighter than the sky 3 degrees away), absent when the sun is 2 degrees
     * below the horizon (the view ray toward it hits the ground). No bloom, to see the disc itself. */
    probe(&ctx, scene(70.0, false), 30.0, 70.0, disc);
    probe(&ctx, scene(70.0, false), 30.0, 67.0, beside);
    printf("noon sun pixel %.1f, 3 deg beside %.3f\n", luminance(disc), luminance(beside));
    CHECK(luminance(disc) > 20.0 * luminance(beside), "no sun disc at noon");
    probe(&ctx, scene(-2.0, false), 30.0, -2.0, hidden);
    printf("sun at -2 deg, pixel toward it %.5f\n", luminance(hidden));
    CHECK(luminance(hidden) < 0.05 * luminance(beside), "sun disc visible below the horizon");

    /* Agreement with the CPU reference (converged, no LUTs, double precision) along a few view axes, bloom
     * off. Converged GPU settings (RGBA32F LUTs, 1024 x 64 multi-scattering samples, 256 view steps) must agree
     * within 1 %: the two implementations of the model are the same model. The defaults (64 x 20 samples,
     * 32 view steps) are an approximation measured in docs/accuracy.md: within 5 % on these views. */
    view_case cases[] = {
        {70.0, 0.0, 90.0}, {70.0, 200.0, 10.0}, {20.0, 30.0, 25.0}, {20.0, 210.0, 5.0}, {2.0, 30.0, 3.0}, {2.0, 120.0, 45.0}};
    sky_lut_quality converged = sky_lut_quality_default();
    converged.lut_f32 = true;
    converged.multiscatter_sqrt_dirs = 32;
    converged.multiscatter_steps = 64;
    float clear_sunward[3] = {0};   /* Earth's converged frame of cases[2], for the haze below */
    for (int quality = 0; quality < 2; ++quality) {
        double worst = 0.0, tol = quality ? 0.01 : 0.05;
        test_renderer t;
        test_renderer_create(&t, &ctx, N, N, false, quality ? &converged : NULL, NULL);
        for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
            float gpu[3];
            double e = versus_reference(&t, quality ? "converged" : "default", cases[i], quality ? 256 : 0, NULL, gpu);
            worst = fmax(worst, e);
            CHECK(e <= tol, "luminance error %.2f%% > %.0f%%", 100 * e, 100 * tol);
            if (quality && i == 2) memcpy(clear_sunward, gpu, sizeof gpu);
        }
        test_renderer_destroy(&t);
        printf("%s settings: max luminance error %.2f%% (bound %.0f%%)\n", quality ? "converged" : "default", 100 * worst, 100 * tol);
    }
    /* A layered medium (Bruneton layer pairs, not the named forms): a 2 km well-mixed haze under an exponential
     * tail, an ozone layer with a flat top, Rayleigh with a linear term and the [0, 1] clamp. The GPU's
     * profile_density() and the reference's model_density() are separate implementations of the same layers:
     * converged settings must agree within 1 % again, and the haze must brighten the sky toward the sun.
     * Converged here includes a 64^2 multi-scattering LUT: the 2 km haze layer's Psi needs the texels (the worst
     * view, measured 2026-11-29: 32^2 0.49 %, 64^2 0.27 %, 128^2 0.27 %, which costs four times 64^2's texels, 30 s
     * more of lavapipe, for nothing). */
    sky_lut_quality converged_layered = converged;
    converged_layered.multiscatter_size = 64;
    model_atmosphere layered = test_layered_atmosphere();
    test_renderer layered_renderer;
    test_renderer_create(&layered_renderer, &ctx, N, N, false, &converged_layered, &layered);
    double worst_layered = 0.0;
    float hazy_sunward[3] = {0};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        float gpu[3];
        double e = versus_reference(&layered_renderer, "layered", cases[i], 256, &layered, gpu);
        worst_layered = fmax(worst_layered, e);
        CHECK(e <= 0.01, "layered medium: luminance error %.2f%% > 1%%", 100 * e);
        /* Sun 20, 25 deg up toward the sun (Mie's forward lobe), against Earth's clear sky of the same view: the
         * converged frame above (held within 1 % of the reference). A clear frame of its own with the 128^2 LUT cost
         * as much as the layered one (40 % of the test's CPU) for a luminance 0.02 % away (0.9232 vs 0.9230), against
         * a bound of 2x (hazy 3.80). */
        if (i == 2) memcpy(hazy_sunward, gpu, sizeof gpu);
    }
    test_renderer_destroy(&layered_renderer);
    printf("layered medium, converged settings: max luminance error %.2f%% (bound 1%%); toward the sun: hazy %.4f, "
           "clear %.4f\n", 100 * worst_layered, luminance(hazy_sunward), luminance(clear_sunward));
    CHECK(luminance(hazy_sunward) > 2.0 * luminance(clear_sunward), "the haze layer does not brighten the sky toward the sun");
    printf("%d frames rendered\n", frames_rendered);
    gpu_context_destroy(&ctx);
    return test_finish("test_sky");
}
