/* "Compute only what the scene needs": turning a feature off changes the recorded pass list and the pipeline
 * variant (specialization constants), not just a uniform; LUTs are recomputed only when the atmosphere
 * changes; the features themselves behave (lit ground, no disc, Cornette-Shanks). Validation on throughout. */
#include "gpu_test.h"
#include "test_atmospheres.h"
#include <string.h>

enum { N = 33 };

typedef struct run {
    char passes[1024];
    char first_passes[1024];      /* the first frame's (with the LUT passes) */
    float centre[3];
    sky_variant variant;
    VkExtent2D ms_extent;
    bool bloom_allocated;
} run;

/* Renders two frames (the second shows what a steady frame records) and returns the second's pass list. */
static run render(gpu_context *ctx, const model_atmosphere *a, const sky_features *f, sky_view v, bool bloom_alloc)
{
    run out;
    memset(&out, 0, sizeof out);
    sky_renderer r;
    sky_renderer_desc desc = {.width = N, .height = N, .readback = true, .bloom = bloom_alloc,
                              .display_format = VK_FORMAT_R8G8B8A8_SRGB};
    sky_renderer_create(&r, ctx, &desc);
    sky_renderer_set_atmosphere(&r, a, SUN_RADIUS_RAD);
    sky_renderer_set_features(&r, f);
    frame_desc fd = {.view = &v};
    FILE *first = fmemopen(out.first_passes, sizeof out.first_passes - 1, "w");
    gpu_barrier_trace_passes(first);
    sky_renderer_render(&r, &fd);
    gpu_barrier_trace_passes(NULL);
    fclose(first);
    FILE *trace = fmemopen(out.passes, sizeof out.passes - 1, "w");
    gpu_barrier_trace_passes(trace);
    sky_renderer_render(&r, &fd);
    gpu_barrier_trace_passes(NULL);
    fclose(trace);
    const uint16_t *half = r.readback_linear.mapped;
    for (int c = 0; c < 3; ++c) out.centre[c] = io_half_to_float(half[4 * ((N / 2) * N + N / 2) + c]);
    out.variant = r.variant;
    out.ms_extent = sky_renderer_lut_extent(&r, 1);
    out.bloom_allocated = r.bloom.mips.image != VK_NULL_HANDLE;
    sky_renderer_destroy(&r);
    return out;
}

int main(void)
{
    gpu_context ctx;
    test_context(&ctx);
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    sky_features defaults = sky_features_default();
    sky_view v = sky_view_default();
    v.fov_deg = 10.0;
    v.sun_elevation_deg = 30.0;
    v.yaw_deg = 180.0;
    v.pitch_deg = 20.0;

    run base = render(&ctx, &earth, &defaults, v, true);
    printf("default passes (steady frame):\n%s", base.passes);
    CHECK(strstr(base.passes, "pass sky\n") && strstr(base.passes, "pass bloom_downsample") && strstr(base.passes, "pass tonemap"),
          "default frame lacks sky/bloom/tonemap");
    CHECK(!strstr(base.passes, "transmittance_lut") && !strstr(base.passes, "multiscatter_lut"),
          "LUTs recomputed in a frame whose atmosphere did not change");

    /* No multi-scattering: no LUT pass (even on the first frame), a 1x1 placeholder, a different variant. */
    sky_features no_ms = defaults;
    no_ms.multiple_scattering = false;
    run ms_off = render(&ctx, &earth, &no_ms, v, true);
    CHECK(ms_off.variant.multiscatter == VK_FALSE && base.variant.multiscatter == VK_TRUE, "variant unchanged");
    /* The multi-scattering LUT is an atlas of three N x N parts (Psi and D | the second bounce's other moments | its
     * zonal moments), N = 32. */
    CHECK(ms_off.ms_extent.width == 0 && base.ms_extent.width == 3 * 32 && base.ms_extent.height == 32,
          "multiscatter image allocated without multi-scattering (%u), or not the 96x32 atlas (%ux%u)", ms_off.ms_extent.width,
          base.ms_extent.width, base.ms_extent.height);
    CHECK(!strstr(ms_off.first_passes, "multiscatter_lut") && strstr(base.first_passes, "multiscatter_lut"),
          "multi-scattering LUT pass recorded without multi-scattering:\n%s", ms_off.first_passes);
    CHECK(ms_off.centre[2] < base.centre[2], "no-multiscatter sky not darker (%g vs %g)", ms_off.centre[2], base.centre[2]);

    /* No bloom: no bloom passes and no mip chain. */
    sky_view no_bloom = v;
    no_bloom.bloom = false;
    run bloom_off = render(&ctx, &earth, &defaults, no_bloom, false);
    CHECK(!strstr(bloom_off.passes, "bloom"), "bloom passes recorded with bloom off:\n%s", bloom_off.passes);
    CHECK(!bloom_off.bloom_allocated && base.bloom_allocated, "bloom mip chain allocated with bloom off");

    /* A species with zero coefficients is compiled out. */
    model_atmosphere no_ozone = earth;
    for (int i = 0; i < 3; ++i) no_ozone.ozone_absorption[i] = 0.0;
    run ozone_off = render(&ctx, &no_ozone, &defaults, v, true);
    CHECK(ozone_off.variant.ozone == VK_FALSE && base.variant.ozone == VK_TRUE, "ozone not compiled out");

    /* Sun disc off: the pixel at the sun is sky only. */
    sky_view at_sun = v;
    at_sun.yaw_deg = 0.0;
    at_sun.pitch_deg = 30.0;
    at_sun.bloom = false;
    sky_features no_disc = defaults;
    no_disc.sun_disc = false;
    run disc = render(&ctx, &earth, &defaults, at_sun, false), nodisc = render(&ctx, &earth, &no_disc, at_sun, false);
    printf("sun pixel: disc %.2f, no disc %.3f\n", luminance(disc.centre), luminance(nodisc.centre));
    CHECK(luminance(disc.centre) > 20.0 * luminance(nodisc.centre), "sun disc not removed");
    CHECK(nodisc.variant.sun_disc == VK_FALSE, "disc variant");

    /* Ground: albedo 0 leaves the ground unlit; albedo 0.3 lights it (looking 30 deg down at noon-ish sun). */
    sky_view down = v;
    down.pitch_deg = -30.0;
    down.bloom = false;
    sky_features ground = defaults;
    ground.ground_albedo[0] = ground.ground_albedo[1] = ground.ground_albedo[2] = 0.3;
    run dark = render(&ctx, &earth, &defaults, down, false), lit = render(&ctx, &earth, &ground, down, false);
    printf("ground: albedo 0 %.4f, albedo 0.3 %.4f\n", luminance(dark.centre), luminance(lit.centre));
    CHECK(lit.variant.ground == VK_TRUE && dark.variant.ground == VK_FALSE, "ground variant");
    /* The ground point is 2 m away (view transmittance 1). Sun-lit part, from the reference's transmittance:
     * E T(0, mu_s) mu_s albedo / pi; the sky's irradiance (the ground-irradiance LUT) adds 5-100 % to it. */
    {
        double t_sun[3];
        double mu_s = sin(v.sun_elevation_deg * TEST_DEG);
        ref_transmittance(&earth, 0.0, mu_s, 4000, t_sun);
        float sun_only[3];
        for (int c = 0; c < 3; ++c) sun_only[c] = (float)(earth.sun_illuminance[c] * t_sun[c] * mu_s * 0.3 / 3.14159265358979);
        double ratio = luminance(lit.centre) / luminance(sun_only);
        printf("ground: lit / sun-only = %.3f (sky irradiance share %.1f %%)\n", ratio, 100.0 * (1.0 - 1.0 / ratio));
        CHECK(ratio > 1.05 && ratio < 2.0, "ground radiance %.4f vs its sun-lit part %.4f: sky irradiance missing or wrong",
              luminance(lit.centre), luminance(sun_only));
    }
    CHECK(strstr(lit.first_passes, "ground_irradiance_lut") && !strstr(dark.first_passes, "ground_irradiance_lut"),
          "ground-irradiance LUT pass not recorded exactly when the ground is lit");

    /* Cornette-Shanks vs Henyey-Greenstein near the sun: different lobes. */
    sky_features cs = defaults;
    cs.mie_phase = VKSKY_MIE_PHASE_CORNETTE_SHANKS;
    sky_view near_sun = at_sun;
    near_sun.pitch_deg = 33.0;
    run hg_run = render(&ctx, &earth, &defaults, near_sun, false), cs_run = render(&ctx, &earth, &cs, near_sun, false);
    printf("3 deg from the sun: HG %.4f, Cornette-Shanks %.4f\n", luminance(hg_run.centre), luminance(cs_run.centre));
    CHECK(fabs(luminance(hg_run.centre) - luminance(cs_run.centre)) > 0.01 * luminance(hg_run.centre), "phase model ignored");
    CHECK(cs_run.variant.mie_phase == VKSKY_MIE_PHASE_CORNETTE_SHANKS, "phase variant");

    /* Density profiles: the shaders get the cheapest exact form as a specialization constant (exponential: one
     * exp; the ozone tent: linear layers, no exp; anything else: the general layer pair). The same densities
     * written as general layer pairs (perturbed by 1e-9 and 1e-12, far below half-float precision) take the
     * general variant and must render the same image. */
    CHECK(base.variant.profile[0] == VKSKY_PROFILE_EXPONENTIAL && base.variant.profile[1] == VKSKY_PROFILE_EXPONENTIAL &&
              base.variant.profile[2] == VKSKY_PROFILE_LINEAR,
          "Earth's profile variant is (%d, %d, %d), expected exponential, exponential, linear", base.variant.profile[0],
          base.variant.profile[1], base.variant.profile[2]);
    {
        model_atmosphere general = earth;
        general.mie_density.layers[0].width = 30.0;
        general.mie_density.layers[1].constant_term = -1e-9;  /* above 30 km (density 1e-11): clamped to 0 */
        general.ozone_density.layers[0].exp_term = 1e-12;     /* exp_scale 0: a constant 1e-12 below 25 km */
        run plain = render(&ctx, &earth, &defaults, v, false), gen = render(&ctx, &general, &defaults, v, false);
        CHECK(gen.variant.profile[0] == VKSKY_PROFILE_EXPONENTIAL && gen.variant.profile[1] == VKSKY_PROFILE_GENERAL &&
                  gen.variant.profile[2] == VKSKY_PROFILE_GENERAL,
              "general layer pairs did not select the general variant (%d, %d, %d)", gen.variant.profile[0],
              gen.variant.profile[1], gen.variant.profile[2]);
        double worst = 0.0;
        for (int c = 0; c < 3; ++c) worst = fmax(worst, fabs(gen.centre[c] - plain.centre[c]) / plain.centre[c]);
        printf("exponential/tent variant vs the general layer pair: centre %.5f %.5f %.5f vs %.5f %.5f %.5f (max rel "
               "diff %.1e)\n", plain.centre[0], plain.centre[1], plain.centre[2], gen.centre[0], gen.centre[1],
               gen.centre[2], worst);
        CHECK(worst < 2e-3, "the general profile path renders %.1e away from the specialised one", worst);
    }

    /* Extra species (beyond Rayleigh, Mie and ozone): one that copies ozone (absorption, tent) and one that copies
     * Rayleigh (scattering, exponential, Rayleigh phase) must render what doubling those species renders: the
     * medium is additive. Zero-coefficient extras are compiled out (variant extra_species 0). */
    {
        model_atmosphere extras, doubled, idle = earth;
        test_extra_species_pair(&earth, &extras, &doubled);
        idle.extra_count = 1;
        idle.extra[0] = (model_extra_species){.name = "nothing", .density = earth.ozone_density};
        sky_view low = v;
        low.pitch_deg = 3.0; /* a long path: the extras matter */
        run with = render(&ctx, &extras, &defaults, low, false), twice = render(&ctx, &doubled, &defaults, low, false);
        run plain = render(&ctx, &earth, &defaults, low, false), none = render(&ctx, &idle, &defaults, low, false);
        double worst = 0.0, change = 0.0;
        for (int c = 0; c < 3; ++c) {
            worst = fmax(worst, fabs(with.centre[c] - twice.centre[c]) / twice.centre[c]);
            change = fmax(change, fabs(twice.centre[c] - plain.centre[c]) / plain.centre[c]);
        }
        printf("extra species copying ozone and Rayleigh: %.5f %.5f %.5f vs doubled species %.5f %.5f %.5f (max rel diff "
               "%.1e; doubling changes the pixel by %.0f %%)\n", with.centre[0], with.centre[1], with.centre[2],
               twice.centre[0], twice.centre[1], twice.centre[2], worst, 100 * change);
        CHECK(with.variant.extra_species == 2 && none.variant.extra_species == 0 && base.variant.extra_species == 0,
              "extra species variant: %d with two, %d with a zero one, %d without", with.variant.extra_species,
              none.variant.extra_species, base.variant.extra_species);
        CHECK(change > 0.05 && worst < 2e-3, "extra species render %.1e away from the doubled species", worst);
        CHECK(memcmp(none.centre, plain.centre, sizeof plain.centre) == 0, "a zero extra species changed the image");
    }

    /* LUTs follow the atmosphere: a changed Rayleigh coefficient recomputes them, a changed Mie g does not with the
     * lesson's model (isotropic multi-scattering LUT) and does with the penumbra's (its first bounce has the real
     * phases, issue 17). */
    {
        sky_renderer r;
        sky_renderer_desc desc = {.width = N, .height = N, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
        sky_renderer_create(&r, &ctx, &desc);
        model_atmosphere lesson = earth;
        lesson.sun_visibility = MODEL_SUN_VISIBILITY_LESSON_FADE;
        sky_renderer_set_atmosphere(&r, &lesson, SUN_RADIUS_RAD);
        frame_desc fd = {.view = &v};
        sky_renderer_render(&r, &fd);
        model_atmosphere g = lesson;
        g.mie_g = 0.5;
        sky_renderer_set_atmosphere(&r, &g, SUN_RADIUS_RAD);
        CHECK(!sky_renderer_luts_dirty(&r), "Mie g made the LUTs dirty (lesson's model)");
        sky_renderer_set_atmosphere(&r, &earth, SUN_RADIUS_RAD);
        sky_renderer_render(&r, &fd);
        g = earth;
        g.mie_g = 0.5;
        sky_renderer_set_atmosphere(&r, &g, SUN_RADIUS_RAD);
        CHECK(sky_renderer_luts_dirty(&r), "Mie g did not make the penumbra's LUTs dirty");
        model_atmosphere thicker = earth;
        thicker.rayleigh_scattering[2] *= 1.1;
        sky_renderer_set_atmosphere(&r, &thicker, SUN_RADIUS_RAD);
        CHECK(sky_renderer_luts_dirty(&r), "a Rayleigh change did not make the LUTs dirty");
        sky_renderer_render(&r, &fd);
        model_atmosphere extra = thicker;
        extra.extra_count = 1;
        extra.extra[0] = (model_extra_species){.name = "no2", .absorption = {1e-4, 4e-4, 9e-4},
                                             .density = model_profile_exponential(1.5)};
        sky_renderer_set_atmosphere(&r, &extra, SUN_RADIUS_RAD);
        CHECK(sky_renderer_luts_dirty(&r), "an extra species did not make the LUTs dirty");
        sky_renderer_render(&r, &fd);
        extra.extra[0].density.layers[1].constant_term = 0.01;
        sky_renderer_set_atmosphere(&r, &extra, SUN_RADIUS_RAD);
        CHECK(sky_renderer_luts_dirty(&r), "an extra species' profile change did not make the LUTs dirty");
        sky_renderer_destroy(&r);
    }

    /* A new scene whose medium and features both change the variant (no ozone, Cornette-Shanks): set together
     * (sky_renderer_set_scene, what the app's sequences, F5 and --spectral call), the pipelines are built once for
     * it, never for a mix of the old and the new scene; the same scene again builds nothing. */
    {
        sky_renderer r;
        sky_renderer_desc desc = {.width = N, .height = N, .display_format = VK_FORMAT_R8G8B8A8_SRGB};
        sky_renderer_create(&r, &ctx, &desc);
        int built = r.variant_builds;
        model_atmosphere no_ozone = earth;
        for (int c = 0; c < 3; ++c) no_ozone.ozone_absorption[c] = 0.0;
        sky_features cs = defaults;
        cs.mie_phase = 1;
        sky_variant before = r.variant;
        sky_renderer_set_scene(&r, &no_ozone, SUN_RADIUS_RAD, &cs);
        CHECK(r.variant.ozone != before.ozone && r.variant.mie_phase != before.mie_phase,
              "the new scene did not change both halves of the variant");
        CHECK(r.variant_builds == built + 1, "a new scene built the variant %d times", r.variant_builds - built);
        sky_renderer_set_scene(&r, &no_ozone, SUN_RADIUS_RAD, &cs);
        CHECK(r.variant_builds == built + 1, "the same scene again rebuilt the variant");
        sky_renderer_destroy(&r);
    }
    gpu_context_destroy(&ctx);
    return test_finish("test_features");
}
