/* LUT readback against the CPU reference (double precision, no LUTs): transmittance at texels including the
 * first/last rows and columns within 1e-3 absolute; the multi-scattering LUT finite, non-negative everywhere
 * (altitude 0 row included) and close to the reference computed with the same direction and step counts. */
#include "gpu_test.h"
#include <string.h>

int main(void)
{
    gpu_context ctx;
    test_context(&ctx);
    sky_view view = sky_view_default();
    view.bloom = false;
    sky_renderer r;
    sky_renderer_desc desc = {.width = 32, .height = 32, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    sky_renderer_create(&r, &ctx, &desc);
    model_atmosphere a;
    model_atmosphere_earth(&a);
    sky_renderer_set_atmosphere(&r, &a, SUN_RADIUS_RAD);
    frame_desc f = {.view = &view};
    sky_renderer_render(&r, &f);

    enum { TW = 256, TH = 64, MN = 32 };   /* the default LUT sizes */
    /* The multi-scattering LUT is VKSKY_MULTISCATTER_PARTS MN x MN parts side by side: Psi^(1/4) and D, the other
     * moments of degree <= 2, the zonal moments. */
    enum { MW = VKSKY_MULTISCATTER_PARTS * MN };
    static float trans[TW * TH * 4], ms[MW * MN * 4];
    test_read_lut(&r, 0, trans);
    test_read_lut(&r, 1, ms);

    /* Transmittance: all four edges, the corners and an interior grid (>= 20 texels). */
    int xs[] = {0, 1, 37, 128, 200, 254, TW - 1};
    int ys[] = {0, 1, 16, 31, 48, 62, TH - 1};
    int checked = 0;
    double worst = 0.0;
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; ++i)
        for (size_t j = 0; j < sizeof ys / sizeof ys[0]; ++j) {
            int x = xs[i], y = ys[j];
            double h, mu, ref[3];
            ref_transmittance_uv_to_params(&a, (x + 0.5) / TW, (y + 0.5) / TH, TW, TH, &h, &mu);
            ref_transmittance(&a, h, mu, 4000, ref);
            const float *gpu = trans + 4 * (y * TW + x);
            for (int c = 0; c < 3; ++c) {
                double err = fabs(gpu[c] - ref[c]);
                if (err > worst) worst = err;
                CHECK(err <= 1e-3, "transmittance texel (%d,%d) h=%.6f mu=%.6f channel %d: gpu %.6f ref %.6f", x, y,
                      h, mu, c, gpu[c], ref[c]);
            }
            ++checked;
        }
    printf("transmittance: %d texels, max abs error %.2e\n", checked, worst);
    CHECK(checked >= 20, "only %d texels checked", checked);

    /* Multi-scattering: every value finite, Psi >= 0 and the moments within [-1, 1] (each is an expectation of a
     * function of the direction bounded by 1, times a share <= 1); Psi compared with the reference at the same
     * counts. */
    int bad = 0;
    for (int y = 0; y < MN; ++y)
        for (int x = 0; x < MW; ++x)
            for (int c = 0; c < 4; ++c) {
                float v = ms[4 * (y * MW + x) + c];
                int is_psi = x < MN && c < 3;
                if (!isfinite(v) || (is_psi ? v < 0.0f : fabsf(v) > 1.0f)) ++bad;
            }
    CHECK(bad == 0, "%d multiscatter LUT values are NaN, Inf, a negative Psi or a moment outside [-1, 1]", bad);
    double worst_rel = 0.0;
    int ms_i[] = {0, 5, 16, 24, 31}, ms_j[] = {0, 1, 8, 20, 31};
    for (size_t i = 0; i < 5; ++i)
        for (size_t j = 0; j < 5; ++j) {
            double h, mu_s, ref[3];
            ref_multiscatter_texel_params(&a, ms_i[i], ms_j[j], MN, MN, &h, &mu_s);
            ref_multiscatter(&a, h, mu_s, 8, 20, 2000, ref);
            const float *stored = ms + 4 * (ms_j[j] * MW + ms_i[i]);
            /* The LUT holds Psi^(1/4) (shaders/glsl/multiscatter_lut.comp). */
            double gpu[3];
            for (int c = 0; c < 3; ++c)
                gpu[c] = pow(stored[c], 4.0);
            for (int c = 0; c < 3; ++c) {
                /* fp16 storage and the LUT-interpolated transmittance vs direct integration. */
                double tol = 0.02 * ref[c] + 2e-6;
                double err = fabs(gpu[c] - ref[c]);
                if (ref[c] > 1e-5 && err / ref[c] > worst_rel) worst_rel = err / ref[c];
                CHECK(err <= tol, "multiscatter texel (%d,%d) h=%.4f mu_s=%.4f channel %d: gpu %.6g ref %.6g",
                      ms_i[i], ms_j[j], h, mu_s, c, gpu[c], ref[c]);
            }
        }
    printf("multiscatter: max relative error %.2e (values > 1e-5)\n", worst_rel);
    sky_renderer_destroy(&r);
    gpu_context_destroy(&ctx);
    return test_finish("test_luts");
}
