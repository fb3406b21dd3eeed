/* Spectral groups as API values (ABI 3, issue 25s): vksky_scene_spectral_group's weights and media against
 * independent computations, and its refusals.
 * - The weights: over every group and channel they sum to the CIE 1931 integrals of the top-of-atmosphere solar
 *   spectrum over 360-830 nm divided by its illuminance (Y: exactly 1; X, Z: the sun's own colour), integrated here
 *   by the trapezoid rule on 0.01 nm steps over the tables' values (vksky integrates bins by Simpson); each bin's
 *   weight is the integral over its own bin; a channel past the last wavelength weighs 0.
 * - The media: Earth's (Hillaire 2020 Table 1) as laws of the wavelength, evaluated here from published forms:
 *   Rayleigh the green value times Bodhaine et al. 1999 eq. (30)'s optical-depth fit's ratio to 550 nm, Mie (Angstrom
 *   exponent 0 through Hillaire's equal red, green and blue values) constant, ozone the green value times the ratio
 *   of the cross-section table's values; the ground's albedo the RGB law (680, 550, 440 nm, linear, held beyond). */
#include <vksky.h>
#include "model/spectrum.h"
#include <math.h>
#include <stdio.h>
#include "../check.h"
#include <string.h>


/* 683 * integral of E(l) cmf(l) over [a, b], the trapezoid rule on steps of at most 0.01 nm. */
static void integral(double a, double b, double out[3])
{
    int steps = (int)ceil((b - a) / 0.01);
    double h = (b - a) / steps;
    out[0] = out[1] = out[2] = 0.0;
    for (int i = 0; i <= steps; ++i) {
        double nm = a + i * h, cmf[3], e = spectrum_solar_irradiance(nm), w = (i == 0 || i == steps) ? 0.5 : 1.0;
        spectrum_cie1931(nm, cmf);
        for (int k = 0; k < 3; ++k) out[k] += w * h * 683.0 * e * cmf[k];
    }
}

/* Bodhaine et al. 1999 eq. (30): Rayleigh optical depth of the standard atmosphere, lambda in micrometres. */
static double bodhaine_tau(double nm)
{
    double l = nm / 1000.0, l2 = l * l;
    return 0.0021520 * (1.0455996 - 341.29061 / l2 - 0.90230850 * l2) / (1.0 + 0.0027059889 / l2 - 85.968563 * l2);
}

static double rgb_law(const double rgb[3], double nm)
{
    if (nm >= 680.0) return rgb[0];
    if (nm <= 440.0) return rgb[2];
    if (nm >= 550.0) return rgb[1] + (rgb[0] - rgb[1]) * (nm - 550.0) / 130.0;
    return rgb[2] + (rgb[1] - rgb[2]) * (nm - 440.0) / 110.0;
}

static void check_weights(const vksky_scene *scene, uint32_t n, uint32_t per_pass)
{
    double whole[3], toa;
    integral(360.0, 830.0, whole);
    toa = whole[1];
    double sum[3] = {0.0, 0.0, 0.0};
    uint32_t groups = vksky_spectral_group_count(n, per_pass);
    CHECK(groups == (n + per_pass - 1) / per_pass, "%u wavelengths, %u a pass: %u groups", n, per_pass, groups);
    for (uint32_t g = 0; g < groups; ++g) {
        vksky_scene *gs = NULL;
        double w[4][3], nm[4];
        vksky_result r = vksky_scene_spectral_group(scene, n, per_pass, g, &gs, w, nm);
        CHECK(r == VKSKY_SUCCESS && gs, "group %u of %u: %d", g, n, (int)r);
        if (r != VKSKY_SUCCESS) continue;
        for (uint32_t c = 0; c < 4; ++c) {
            uint32_t i = per_pass * g + c;
            if (c >= per_pass || i >= n) {
                CHECK(w[c][0] == 0.0 && w[c][1] == 0.0 && w[c][2] == 0.0, "n %u group %u channel %u: not 0", n, g, c);
                continue;
            }
            double width = 470.0 / n, bin[3];
            CHECK(fabs(nm[c] - (360.0 + (i + 0.5) * width)) < 1e-9, "bin %u of %u: centre %.6f nm", i, n, nm[c]);
            integral(360.0 + i * width, 360.0 + (i + 1) * width, bin);
            for (int k = 0; k < 3; ++k) {
                CHECK(fabs(w[c][k] * toa - bin[k]) <= 1e-5 * whole[1] / n + 1e-5 * fabs(bin[k]),
                      "bin %u of %u, %c: %.8g against the bin's integral %.8g", i, n, "XYZ"[k], w[c][k] * toa, bin[k]);
                sum[k] += w[c][k];
            }
        }
        vksky_scene_destroy(gs);
    }
    for (int k = 0; k < 3; ++k)
        CHECK(fabs(sum[k] - whole[k] / toa) < 2e-5, "%u wavelengths, %u a pass: %c weights sum to %.8f, the solar "
              "spectrum's integral over its illuminance is %.8f", n, per_pass, "XYZ"[k], sum[k], whole[k] / toa);
    CHECK(fabs(sum[1] - 1.0) < 2e-5, "%u wavelengths: the Y weights sum to %.8f, not 1", n, sum[1]);
    printf("api_spectral: %u wavelengths, %u a pass: weights sum X %.6f Y %.6f Z %.6f (integrals %.6f 1 %.6f)\n", n,
           per_pass, sum[0], sum[1], sum[2], whole[0] / toa, whole[2] / toa);
}

static void check_media(const vksky_scene *scene, uint32_t n, uint32_t per_pass, const double albedo[3])
{
    const double rayleigh_green = 13.558e-3, ozone_green = 1.881e-3, mie_s = 3.996e-3, mie_a = 0.444e-3;
    double worst[3] = {0.0, 0.0, 0.0};
    for (uint32_t g = 0; g < vksky_spectral_group_count(n, per_pass); ++g) {
        vksky_scene *gs = NULL;
        double w[4][3], nm[4];
        if (vksky_scene_spectral_group(scene, n, per_pass, g, &gs, w, nm) != VKSKY_SUCCESS) {
            CHECK(0, "group %u", g);
            continue;
        }
        for (uint32_t c = 0; c < per_pass && per_pass * g + c < n; ++c) {
            vksky_spectral_coefficients k;
            CHECK(vksky_scene_spectral_coefficients(gs, c, &k) == VKSKY_SUCCESS, "group %u channel %u", g, c);
            double rayleigh = rayleigh_green * bodhaine_tau(nm[c]) / bodhaine_tau(550.0);
            double ozone = ozone_green * spectrum_ozone_cross_section(nm[c]) / spectrum_ozone_cross_section(550.0);
            double e[3] = {fabs(k.rayleigh_scattering / rayleigh - 1.0), fabs(k.ozone_absorption / ozone - 1.0),
                           fabs(k.mie_scattering - mie_s) + fabs(k.mie_absorption - mie_a)};
            for (int q = 0; q < 3; ++q) worst[q] = fmax(worst[q], e[q]);
            /* Bodhaine's fit is within 0.01 % of the formula the medium evaluates (ctest spectral) */
            CHECK(e[0] < 1e-3, "%.2f nm: Rayleigh %.6g /km against Bodhaine's law %.6g", nm[c], k.rayleigh_scattering,
                  rayleigh);
            CHECK(e[1] < 1e-9, "%.2f nm: ozone %.6g /km against the cross sections' %.6g", nm[c], k.ozone_absorption,
                  ozone);
            CHECK(e[2] < 1e-12, "%.2f nm: Mie %.6g, %.6g /km: not Hillaire's constant", nm[c], k.mie_scattering,
                  k.mie_absorption);
            CHECK(fabs(k.ground_albedo - rgb_law(albedo, nm[c])) < 1e-12, "%.2f nm: albedo %.6f against %.6f", nm[c],
                  k.ground_albedo, rgb_law(albedo, nm[c]));
        }
        vksky_spectral_coefficients k;
        CHECK(vksky_scene_spectral_coefficients(gs, per_pass, &k) == VKSKY_ERROR_INVALID_ARGUMENT,
              "a channel past per_pass accepted");
        vksky_scene *again = NULL;
        CHECK(vksky_scene_spectral_group(gs, n, per_pass, 0, &again, w, NULL) == VKSKY_ERROR_INVALID_ARGUMENT && !again,
              "a group scene split again");
        vksky_scene_destroy(gs);
    }
    printf("api_spectral: %u wavelengths, %u a pass: worst relative Rayleigh %.2e, ozone %.2e; Mie %.1e\n", n,
           per_pass, worst[0], worst[1], worst[2]);
}

int main(void)
{
    CHECK(vksky_abi_version() == VKSKY_ABI_VERSION && VKSKY_ABI_VERSION >= 3u, "ABI %u", vksky_abi_version());
    vksky_scene *earth = NULL, *lit = NULL;
    if (vksky_scene_create_earth(&earth) != VKSKY_SUCCESS) return 1;
    char *argv[] = {"vksky", "--ground-albedo", "0.3,0.2,0.1", NULL};
    if (vksky_scene_from_args(3, argv, NULL, NULL, &lit) != VKSKY_SUCCESS) return 1;
    const uint32_t counts[] = {8, 24, 48, 9, 7};
    for (int i = 0; i < 5; ++i)
        for (uint32_t p = 3; p <= 4; ++p) check_weights(earth, counts[i], p);
    const double albedo[3] = {0.3, 0.2, 0.1};
    check_media(lit, 24, 4, albedo);
    check_media(lit, 8, 3, albedo);
    /* Refusals: out of range, a group past the last, a non-group scene's coefficients. */
    vksky_scene *gs = (vksky_scene *)1;
    double w[4][3];
    CHECK(vksky_spectral_group_count(2, 3) == 0 && vksky_spectral_group_count(49, 4) == 0 &&
          vksky_spectral_group_count(8, 5) == 0, "out-of-range counts accepted");
    CHECK(vksky_scene_spectral_group(earth, 8, 4, 2, &gs, w, NULL) == VKSKY_ERROR_INVALID_ARGUMENT && !gs,
          "group 2 of 8 four a pass accepted");
    CHECK(vksky_scene_spectral_group(earth, 8, 2, 0, &gs, w, NULL) == VKSKY_ERROR_INVALID_ARGUMENT, "2 a pass");
    vksky_spectral_coefficients k;
    CHECK(vksky_scene_spectral_coefficients(earth, 0, &k) == VKSKY_ERROR_INVALID_ARGUMENT, "an RGB scene's channel");
    /* The XYZ -> Rec.709 matrix: D65's white (x 0.3127, y 0.3290, Y 1) is Rec.709's white (1, 1, 1). */
    double d65[3] = {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290}, rgb[3];
    vksky_spectral_xyz_to_rec709(d65, rgb);
    for (int c = 0; c < 3; ++c) CHECK(fabs(rgb[c] - 1.0) < 2e-3, "D65 white -> channel %d = %.5f", c, rgb[c]);
    vksky_scene_destroy(earth);
    vksky_scene_destroy(lit);
    if (check_failures) fprintf(stderr, "api_spectral: %d check_failures\n", check_failures);
    else printf("api_spectral: ok\n");
    return check_failures ? 1 : 0;
}
