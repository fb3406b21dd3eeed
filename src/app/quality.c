#include "app/quality.h"
#include <math.h>
#include <string.h>

#define DEFAULT_LUTS .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, \
                     .multiscatter_size = 32, .multiscatter_sqrt_dirs = 8, .multiscatter_steps = 20

/* The presets. low/medium: the sky-view LUT path (interactive); high: the per-pixel march with a better
 * multi-scattering LUT; ultra: near-converged (the LUTs are computed once per atmosphere, so their quality
 * costs nothing per frame). */
const quality_config quality_presets[4] = {
    {.name = "low", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO, .steps = 16, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16, DEFAULT_LUTS, .render_scale = 0.5, .bloom_mips = 4},
    {.name = "medium", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, .transmittance_width = 256,
     .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32, .multiscatter_sqrt_dirs = 32,
     .multiscatter_steps = 20, .render_scale = 1.0, .bloom_mips = 5},
    {.name = "high", .mode = SKY_CHOICE_MARCH, .pass_kind = SKY_PASS_AUTO, .steps = 64, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, .transmittance_width = 256,
     .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32, .multiscatter_sqrt_dirs = 32,
     .multiscatter_steps = 32, .render_scale = 1.0, .bloom_mips = 5},
    {.name = "ultra", .mode = SKY_CHOICE_MARCH, .pass_kind = SKY_PASS_AUTO, .steps = 128, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 384, .skyview_height = 216, .skyview_steps = 64, .transmittance_width = 512,
     .transmittance_height = 128, .transmittance_steps = 80, .multiscatter_size = 64, .multiscatter_sqrt_dirs = 32,
     .multiscatter_steps = 64, .lut_f32 = true, .render_scale = 1.0, .bloom_mips = 5},
};

#define MARCH(n, s, d) {.name = n, .mode = SKY_CHOICE_MARCH, .steps = s, .step_distribution = d, .sample_offset = 0.5, \
                        .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5}
#define SKYVIEW(n, w, h, s) {.name = n, .mode = SKY_CHOICE_AUTO, .steps = 32, .step_distribution = 2, .sample_offset = 0.5, \
                             .skyview_width = w, .skyview_height = h, .skyview_steps = s, DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5}

const quality_config quality_sweep[] = {
    MARCH("march8", 8, 2), MARCH("march16", 16, 2), MARCH("march32", 32, 2), MARCH("march64", 64, 2),
    MARCH("march128", 128, 2), MARCH("march32-uniform", 32, 1), MARCH("march8-uniform", 8, 1),
    {.name = "march32-offset0.3", .mode = SKY_CHOICE_MARCH, .steps = 32, .step_distribution = 2, .sample_offset = 0.3,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5},
    {.name = "march-variable8-64", .mode = SKY_CHOICE_MARCH, .steps = 8, .max_steps = 64, .step_distribution = 2,
     .sample_offset = 0.5, .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS,
     .render_scale = 1, .bloom_mips = 5},
    SKYVIEW("skyview96x54", 96, 54, 16), SKYVIEW("skyview192x108", 192, 108, 30),
    SKYVIEW("skyview384x216", 384, 216, 30), SKYVIEW("skyview192x108-s60", 192, 108, 60),
    {.name = "skyview-compute", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_COMPUTE, .steps = 32,
     .step_distribution = 2, .sample_offset = 0.5, .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30,
     DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5},
    {.name = "march32-compute", .mode = SKY_CHOICE_MARCH, .pass_kind = SKY_PASS_COMPUTE, .steps = 32,
     .step_distribution = 2, .sample_offset = 0.5, .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30,
     DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5},
    {.name = "march32-ms256", .mode = SKY_CHOICE_MARCH, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, .transmittance_width = 256,
     .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32, .multiscatter_sqrt_dirs = 16,
     .multiscatter_steps = 20, .render_scale = 1, .bloom_mips = 5},
    {.name = "march32-f32", .mode = SKY_CHOICE_MARCH, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS, .lut_f32 = true,
     .render_scale = 1, .bloom_mips = 5},
    {.name = "fill-fragment", .mode = SKY_CHOICE_FILL, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5},
    {.name = "fill-compute", .mode = SKY_CHOICE_FILL, .pass_kind = SKY_PASS_COMPUTE, .steps = 32,
     .step_distribution = 2, .sample_offset = 0.5, .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30,
     DEFAULT_LUTS, .render_scale = 1, .bloom_mips = 5},
    /* Candidates for a CPU device's window (lavapipe, issue 16): medium's LUTs (multi-scattering with 1024
     * directions, computed once) with low's sky-view LUT, at full size and at 0.75. */
    {.name = "medium-skyview96", .mode = SKY_CHOICE_AUTO, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16, .transmittance_width = 256,
     .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32, .multiscatter_sqrt_dirs = 32,
     .multiscatter_steps = 20, .render_scale = 1, .bloom_mips = 5},
    {.name = "medium-skyview96-scale0.75", .mode = SKY_CHOICE_AUTO, .steps = 32, .step_distribution = 2,
     .sample_offset = 0.5, .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16,
     .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32,
     .multiscatter_sqrt_dirs = 32, .multiscatter_steps = 20, .render_scale = 0.75, .bloom_mips = 5},
    {.name = "medium-skyview96-scale0.5", .mode = SKY_CHOICE_AUTO, .steps = 32, .step_distribution = 2,
     .sample_offset = 0.5, .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16,
     .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32,
     .multiscatter_sqrt_dirs = 32, .multiscatter_steps = 20, .render_scale = 0.5, .bloom_mips = 5},
    {.name = "march32-scale0.5", .mode = SKY_CHOICE_MARCH, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 192, .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS, .render_scale = 0.5, .bloom_mips = 5},
};
const int quality_sweep_count = (int)(sizeof quality_sweep / sizeof quality_sweep[0]);

const quality_config quality_lesson = {.name = "lesson", .mode = SKY_CHOICE_MARCH, .pass_kind = SKY_PASS_AUTO,
                                       .steps = 32, .step_distribution = 2, .sample_offset = 0.5, .skyview_width = 192,
                                       .skyview_height = 108, .skyview_steps = 30, DEFAULT_LUTS, .render_scale = 1,
                                       .bloom_mips = 5};

const quality_config *quality_preset(const char *name)
{
    for (int i = 0; i < 4; ++i)
        if (!strcmp(quality_presets[i].name, name)) return &quality_presets[i];
    if (!strcmp(name, "lesson")) return &quality_lesson;
    return NULL;
}

void quality_apply(const quality_config *q, sky_view *v, sky_lut_quality *lut, double *render_scale, int *bloom_mips)
{
    v->mode = q->mode;
    v->pass_kind = q->pass_kind;
    v->steps = q->steps;
    v->max_steps = q->max_steps;
    v->step_distribution = q->step_distribution;
    v->sample_offset = q->sample_offset;
    v->skyview_steps = q->skyview_steps;
    lut->skyview_width = q->skyview_width;
    lut->skyview_height = q->skyview_height;
    lut->transmittance_width = q->transmittance_width;
    lut->transmittance_height = q->transmittance_height;
    lut->transmittance_steps = q->transmittance_steps;
    lut->multiscatter_size = q->multiscatter_size;
    lut->multiscatter_sqrt_dirs = q->multiscatter_sqrt_dirs;
    lut->multiscatter_steps = q->multiscatter_steps;
    lut->lut_f32 = q->lut_f32;
    *render_scale = q->render_scale;
    *bloom_mips = q->bloom_mips;
}

/* Noon, afternoon, sunset, twilight, 10 km looking at the horizon, 400 km looking down at the limb. */
const quality_scene quality_scenes[6] = {
    {"noon", 0.001, 70.0, 180.0, 35.0, 90.0, 0.0},
    {"afternoon", 0.001, 20.0, 30.0, 20.0, 90.0, 0.0},
    {"sunset", 0.001, 2.0, 0.0, 15.0, 90.0, 1.0},
    {"twilight", 0.001, -4.0, 0.0, 15.0, 90.0, 10.0},
    {"10km-horizon", 10.0, 30.0, 90.0, 0.0, 60.0, 0.0},
    {"400km-limb", 400.0, 20.0, 0.0, -19.0, 40.0, 0.0},
};

int quality_scene_class(double altitude_km, double sun_elevation_deg)
{
    if (altitude_km >= 100.0) return 5;
    if (altitude_km >= 3.0) return 4;
    if (sun_elevation_deg < -1.0) return 3;
    if (sun_elevation_deg < 8.0) return 2;
    if (sun_elevation_deg < 45.0) return 1;
    return 0;
}

#include "app/quality_table.h"

const quality_config *quality_pick(double max_error, double altitude_km, double sun_elevation_deg, double *measured,
                                   const char **scene_name)
{
    int scene = quality_scene_class(altitude_km, sun_elevation_deg);
    *scene_name = quality_scenes[scene].name;
    const quality_config *best = NULL;
    double best_ms = INFINITY;
    for (int i = 0; i < quality_table_count; ++i) {
        const quality_measurement *m = &quality_table[i];
        if (m->scene != scene || !(m->err_mean <= max_error) || m->gpu_ms >= best_ms) continue;
        for (int k = 0; k < quality_sweep_count; ++k)
            if (!strcmp(quality_sweep[k].name, m->config)) best = &quality_sweep[k];
        for (int k = 0; k < 4; ++k)
            if (!strcmp(quality_presets[k].name, m->config)) best = &quality_presets[k];
        best_ms = m->gpu_ms;
        *measured = m->err_mean;
    }
    return best;
}

const quality_config *quality_auto(double altitude_km, double sun_elevation_deg, double *measured,
                                   const char **scene_name)
{
    int scene = quality_scene_class(altitude_km, sun_elevation_deg);
    double best = INFINITY;
    for (int i = 0; i < quality_table_count; ++i)
        if (quality_table[i].scene == scene && quality_table[i].err_mean < best) best = quality_table[i].err_mean;
    double budget = fmax(QUALITY_AUTO_FLOOR, QUALITY_AUTO_SLACK * best);
    return quality_pick(budget, altitude_km, sun_elevation_deg, measured, scene_name);
}
