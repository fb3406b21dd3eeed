#include "app/quality/quality.h"
#include "sky/shaders.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_LUTS .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, \
                     .multiscatter_size = 32, .multiscatter_sqrt_dirs = 8, .multiscatter_steps = 20

/* The presets. low/medium: the sky-view LUT path (interactive); high: the per-pixel march with a better
 * multi-scattering LUT; ultra: near-converged (the LUTs are computed once per atmosphere, so their quality
 * costs nothing per frame; its 128^2 multi-scattering LUT follows the penumbra's Psi across the terminator:
 * 64^2 is 1.2 % off the reference on the anti-sun sky at sun -2, 128^2 0.6 %). */
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
     .transmittance_height = 128, .transmittance_steps = 80, .multiscatter_size = 128, .multiscatter_sqrt_dirs = 32,
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
     * directions, computed once) with low's sky-view LUT, at full size, 0.75 and 0.5 (--quality cpu). The sky pass
     * kind by device, as the presets. */
    {.name = "medium-skyview96", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO, .steps = 32, .step_distribution = 2, .sample_offset = 0.5,
     .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16, .transmittance_width = 256,
     .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32, .multiscatter_sqrt_dirs = 32,
     .multiscatter_steps = 20, .render_scale = 1, .bloom_mips = 5},
    {.name = "medium-skyview96-scale0.75", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO, .steps = 32, .step_distribution = 2,
     .sample_offset = 0.5, .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16,
     .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32,
     .multiscatter_sqrt_dirs = 32, .multiscatter_steps = 20, .render_scale = 0.75, .bloom_mips = 5},
    {.name = "medium-skyview96-scale0.5", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO, .steps = 32, .step_distribution = 2,
     .sample_offset = 0.5, .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16,
     .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32,
     .multiscatter_sqrt_dirs = 32, .multiscatter_steps = 20, .render_scale = 0.5, .bloom_mips = 5},
    /* --quality cpu: the half-size sky with the bloom chain from a quarter-size mip 0 (the bloom is a fifth of a
     * CPU device's frame at half size; the error is measured with bloom off, so the same as scale0.5's). */
    {.name = "medium-skyview96-scale0.5-bloomq", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO, .steps = 32,
     .step_distribution = 2, .sample_offset = 0.5, .skyview_width = 96, .skyview_height = 54, .skyview_steps = 16,
     .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40, .multiscatter_size = 32,
     .multiscatter_sqrt_dirs = 32, .multiscatter_steps = 20, .render_scale = 0.5, .bloom_mips = 5,
     .bloom_quarter = true},
    /* --quality cpu since the second bounce's moments (issue 17): 24 sky-view steps. With 16 the afternoon (sun 20°)
     * measured 1.05 % on lavapipe (0.95 % under the earlier model), over the 1 % a CPU device's daytime point
     * promises; 24 steps: 0.63 %, noon 0.80 -> 0.47 %, for ~3 ms of CPU a frame. */
    {.name = "medium-skyview96-s24-scale0.5-bloomq", .mode = SKY_CHOICE_AUTO, .pass_kind = SKY_PASS_AUTO,
     .steps = 32, .step_distribution = 2, .sample_offset = 0.5, .skyview_width = 96, .skyview_height = 54,
     .skyview_steps = 24, .transmittance_width = 256, .transmittance_height = 64, .transmittance_steps = 40,
     .multiscatter_size = 32, .multiscatter_sqrt_dirs = 32, .multiscatter_steps = 20, .render_scale = 0.5,
     .bloom_mips = 5, .bloom_quarter = true},
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
    if (!strcmp(name, "cpu"))      /* the CPU device's point: a sweep configuration under a short name */
        for (int k = 0; k < quality_sweep_count; ++k)
            if (!strcmp(quality_sweep[k].name, QUALITY_CPU_CONFIG)) return &quality_sweep[k];
    return NULL;
}

void quality_apply(const quality_config *q, sky_view *v, sky_lut_quality *lut, double *render_scale, int *bloom_mips,
                   bool *bloom_quarter)
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
    *bloom_quarter = q->bloom_quarter;
}

/* Noon, afternoon, sunset, twilight, 10 km looking at the horizon, 400 km looking down at the limb; the sun on the
 * horizon and twilight at -2 deg (sunset and twilight are where the model's error and the presets' differ most). */
const quality_scene quality_scenes[QUALITY_SCENE_COUNT] = {
    {"noon", 0.001, 70.0, 180.0, 35.0, 90.0, 0.0},
    {"afternoon", 0.001, 20.0, 30.0, 20.0, 90.0, 0.0},
    {"sunset", 0.001, 2.0, 0.0, 15.0, 90.0, 1.0},
    {"twilight", 0.001, -4.0, 0.0, 15.0, 90.0, 10.0},
    {"10km-horizon", 10.0, 30.0, 90.0, 0.0, 60.0, 0.0},
    {"400km-limb", 400.0, 20.0, 0.0, -19.0, 40.0, 0.0},
    {"sun0", 0.001, 0.0, 0.0, 15.0, 90.0, 2.0},
    {"twilight-2", 0.001, -2.0, 0.0, 15.0, 90.0, 5.0},
};

int quality_scene_class(double altitude_km, double sun_elevation_deg)
{
    if (altitude_km >= 100.0) return 5;
    if (altitude_km >= 3.0) return 4;
    if (sun_elevation_deg < -3.0) return 3;
    if (sun_elevation_deg < -1.0) return 7;
    if (sun_elevation_deg < 1.0) return 6;
    if (sun_elevation_deg < 8.0) return 2;
    if (sun_elevation_deg < 45.0) return 1;
    return 0;
}

#include "app/quality/quality_table.h"
#include "app/quality/quality_table_cpu.h"
#include "app/quality/quality_horizon_table.h"

/* The horizon-band error (max over the pixels within 2 px of the horizon against the per-pixel march) of a
 * configuration on class c (tools/tradeoff --emit-horizon-table). A class the table does not cover: 0 (no check); a
 * configuration the table lacks on a class it covers: infinite (not known to be within any bound, so refused). */
static double horizon_max(const char *config, int c)
{
    bool covered = false;
    for (int i = 0; i < quality_horizon_table_count; ++i) {
        if (quality_horizon_table[i].scene != c) continue;
        covered = true;
        if (!strcmp(quality_horizon_table[i].config, config)) return quality_horizon_table[i].max;
    }
    return covered ? INFINITY : 0.0;
}

/* The configuration a table row names (the sweep's, or a preset measured under its own name). */
static const quality_config *config_named(const char *name)
{
    for (int k = 0; k < 4; ++k)
        if (!strcmp(quality_presets[k].name, name)) return &quality_presets[k];
    for (int k = 0; k < quality_sweep_count; ++k)
        if (!strcmp(quality_sweep[k].name, name)) return &quality_sweep[k];
    return NULL;
}

/* The class whose rows stand for class c in a table: c itself, or, in a table measured before the sun-on-the-
 * horizon and -2 deg twilight classes joined (the CPU device's), the class next to it (sunset, twilight). */
static int measured_class(const quality_measurement *table, int count, int c)
{
    for (int i = 0; i < count; ++i)
        if (table[i].scene == c) return c;
    return c == 6 ? 2 : c == 7 ? 3 : c;
}

/* The cheapest configuration of a measured table whose error is within budget[class] on every class of the set
 * (a bitmask of quality_scenes indices). Its cost on a set is its dearest class: a sequence that passes from noon
 * to twilight keeps one configuration, the one that serves its hardest frame. *measured: its largest error. */
static const quality_config *pick_from(const quality_measurement *table, int count, const double *budget,
                                       unsigned classes, double *measured, bool horizon)
{
    unsigned rows = 0;   /* the classes of the table's rows that stand for the set */
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
        if (classes >> c & 1u) rows |= 1u << measured_class(table, count, c);
    const quality_config *best = NULL;
    double best_ms = INFINITY;
    for (int i = 0; i < count; ++i) {
        if (!(rows >> table[i].scene & 1u)) continue;
        bool first_row = true;   /* each configuration once: at its first row on a class of the set */
        for (int j = 0; j < i; ++j)
            if (rows >> table[j].scene & 1u && !strcmp(table[j].config, table[i].config)) first_row = false;
        if (!first_row) continue;
        double ms = 0.0, err = 0.0;
        bool serves_all = true;
        for (int c = 0; c < QUALITY_SCENE_COUNT && serves_all; ++c) {
            if (!(rows >> c & 1u)) continue;
            const quality_measurement *row = NULL;
            for (int j = 0; j < count; ++j)
                if (table[j].scene == c && !strcmp(table[j].config, table[i].config)) row = &table[j];
            serves_all = row && row->err_mean <= budget[c];
            /* --max-error: the rows at the horizon too (issue 26), which a whole frame's mean cannot see. */
            if (serves_all && horizon) serves_all = horizon_max(table[i].config, c) <= budget[c];
            if (serves_all) ms = fmax(ms, row->gpu_ms), err = fmax(err, row->err_mean);
        }
        const quality_config *q = config_named(table[i].config);
        if (!serves_all || !q || ms >= best_ms) continue;
        best = q, best_ms = ms, *measured = err;
    }
    return best;
}

void quality_class_names(unsigned classes, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c)
        if (classes >> c & 1u && used < size)
            used += (size_t)snprintf(out + used, size - used, "%s%s", used ? "+" : "", quality_scenes[c].name);
}

const quality_config *quality_pick(double max_error, unsigned classes, bool cpu_device, double *measured)
{
    /* The running device's table (issue 31): on lavapipe the GPU's costs would pick by another machine's speed and
     * quote another device's measurement. */
    const quality_measurement *table = cpu_device ? quality_table_cpu : quality_table;
    int count = cpu_device ? quality_table_cpu_count : quality_table_count;
    double budget[QUALITY_SCENE_COUNT];
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c) budget[c] = max_error;
    return pick_from(table, count, budget, classes, measured, true);
}

const quality_config *quality_auto(unsigned classes, bool cpu_device, double *measured)
{
    const quality_measurement *table = cpu_device ? quality_table_cpu : quality_table;
    int count = cpu_device ? quality_table_cpu_count : quality_table_count;
    double budget[QUALITY_SCENE_COUNT];
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c) {
        double best = INFINITY;
        for (int i = 0; i < count; ++i)
            if (table[i].scene == c && table[i].err_mean < best) best = table[i].err_mean;
        budget[c] = fmax(QUALITY_AUTO_FLOOR, QUALITY_AUTO_SLACK * best);
    }
    return pick_from(table, count, budget, classes, measured, false);
}

/* The knobs of a configuration as text (no struct padding in the hash), hashed with FNV-1a. */
static unsigned long knob_hash(unsigned long h, const quality_config *q)
{
    char text[320];
    snprintf(text, sizeof text, "%s %d %d %d %d %.9g %.9g %d %d %d %d %d %d %d %d %d %d %.9g %d %d;", q->name,
             (int)q->mode, (int)q->pass_kind, q->steps, q->max_steps, q->step_distribution, q->sample_offset,
             q->skyview_width, q->skyview_height, q->skyview_steps, q->transmittance_width, q->transmittance_height,
             q->transmittance_steps, q->multiscatter_size, q->multiscatter_sqrt_dirs, q->multiscatter_steps,
             (int)q->lut_f32, q->render_scale, q->bloom_mips, (int)q->bloom_quarter);
    for (const char *c = text; *c; ++c) h = (h ^ (unsigned char)*c) * 16777619ul & 0xfffffffful;
    return h;
}

void quality_names_key(const char *const *names, int count, char *out, size_t size)
{
    unsigned long h = 2166136261ul;
    for (int i = 0; i < count; ++i) {
        bool first = true;   /* each configuration once, in order of first appearance */
        for (int j = 0; j < i && first; ++j) first = strcmp(names[i], names[j]) != 0;
        const quality_config *q = first ? config_named(names[i]) : NULL;
        if (q) h = knob_hash(h, q);
    }
    snprintf(out, size, "%s/%08lx", sky_image_shaders_key(), h);
}

void quality_table_key(bool cpu_device, char *out, size_t size)
{
    const quality_measurement *table = cpu_device ? quality_table_cpu : quality_table;
    int count = cpu_device ? quality_table_cpu_count : quality_table_count;
    const char *names[256];
    int n = 0;
    for (int i = 0; i < count && n < 256; ++i) names[n++] = table[i].config;
    quality_names_key(names, n, out, size);
}

const char *quality_table_recorded_key(bool cpu_device) { return cpu_device ? QUALITY_TABLE_CPU_KEY : QUALITY_TABLE_KEY; }

const char *quality_table_estimate(bool cpu_device)
{
    char key[96];
    quality_table_key(cpu_device, key, sizeof key);
    if (!strcmp(key, quality_table_recorded_key(cpu_device))) return NULL;
#ifdef QUALITY_TABLE_ESTIMATE
    if (!cpu_device) return QUALITY_TABLE_ESTIMATE;
#endif
#ifdef QUALITY_TABLE_CPU_ESTIMATE
    if (cpu_device) return QUALITY_TABLE_CPU_ESTIMATE;
#endif
    return "measured with other shaders or knobs than this build's";
}

sky_view quality_scene_view(const quality_scene *s)
{
    sky_view v = sky_view_default();
    v.altitude_km = s->altitude_km;
    v.sun_elevation_deg = s->sun_elevation_deg;
    v.sun_azimuth_deg = 0.0;
    v.yaw_deg = s->yaw_deg;
    v.pitch_deg = s->pitch_deg;
    v.fov_deg = s->fov_deg;
    v.exposure_ev = s->exposure_ev;
    return v;
}

#include "app/quality/quality_color_table.h"

double quality_color_error(int wavelengths, int c)
{
    for (int i = 0; i < quality_color_table_count; ++i)
        if (quality_color_table[i].wavelengths == wavelengths && c >= 0 && c < QUALITY_SCENE_COUNT)
            return quality_color_table[i].worst_de[c];
    return INFINITY;
}

int quality_color_settings(int *out, int max)
{
    int n = 0;
    for (int i = 0; i < quality_color_table_count && n < max; ++i) out[n++] = quality_color_table[i].wavelengths;
    return n;
}
