/* Quality configurations: the speed/accuracy knobs as one value, the four presets, the scene classes of the
 * trade-off measurement, and the measured table --max-error chooses from. */
#ifndef VKSKY_APP_QUALITY_H
#define VKSKY_APP_QUALITY_H
#include "sky/renderer.h"
#include <stddef.h>

typedef struct quality_config {
    const char *name;
    sky_mode_choice mode;
    sky_pass_kind pass_kind;
    int steps, max_steps;                  /* view march (max 0: fixed) */
    double step_distribution, sample_offset;
    int skyview_width, skyview_height, skyview_steps;
    int transmittance_width, transmittance_height, transmittance_steps;
    int multiscatter_size, multiscatter_sqrt_dirs, multiscatter_steps;
    bool lut_f32;
    double render_scale;
    int bloom_mips;
    bool bloom_quarter;                    /* the bloom chain from a quarter-size mip 0 (--bloom-res quarter) */
} quality_config;

/* low, medium, high, ultra, lesson, cpu (NULL if unknown; "auto" is not a fixed configuration: quality_auto). */
const quality_config *quality_preset(const char *name);
extern const quality_config quality_presets[4];
/* The lesson's configuration (the defaults before --quality auto: the 32-step march, the lesson's LUTs), kept
 * for comparison and for the guide: --quality lesson. The same knobs as the sweep's "march32". */
extern const quality_config quality_lesson;
/* --quality cpu: the measured point for a CPU device (lavapipe 1280x720, quality_table_cpu.h): medium's LUTs, a
 * 96x54 sky-view LUT with 24 steps (16 until issue 17's moments put the afternoon over 1 %), the sky at half size
 * (at 1280x720 the half-size sky adds < 0.05 % to the mean error: the sky-view LUT is coarser than a half-size
 * pixel), the bloom chain from a quarter-size mip 0 (a fifth less CPU a frame than from half size:
 * docs/readme/post.md). */
#define QUALITY_CPU_CONFIG "medium-skyview96-s24-scale0.5-bloomq"
/* The configurations tools/tradeoff sweeps (presets included). */
extern const quality_config quality_sweep[];
extern const int quality_sweep_count;

/* Apply a configuration's knobs to a view and a renderer description. */
void quality_apply(const quality_config *q, sky_view *v, sky_lut_quality *lut, double *render_scale, int *bloom_mips,
                   bool *bloom_quarter);

/* The scene set of the trade-off measurement. */
typedef struct quality_scene {
    const char *name;
    double altitude_km, sun_elevation_deg, yaw_deg, pitch_deg, fov_deg, exposure_ev;
} quality_scene;
/* Noon, afternoon, sunset (+2), twilight (-4), 10 km, 400 km, then (issue 17) the sun on the horizon (0) and
 * twilight at -2: indices are the table's scene numbers (quality_table.h), so new scenes go at the end. */
#define QUALITY_SCENE_COUNT 8
extern const quality_scene quality_scenes[QUALITY_SCENE_COUNT];
/* The view a measured scene is rendered with (the default view, its camera, sun elevation and exposure; the sun at
 * azimuth 0): what tools/tradeoff measured the tables on and ctest promise re-measures. */
sky_view quality_scene_view(const quality_scene *s);
/* The scene class a view belongs to (nearest by sun elevation and altitude). */
int quality_scene_class(double altitude_km, double sun_elevation_deg);

/* The scene classes a choice serves, as a bitmask of quality_scenes indices: one view's class, or every class the
 * frames of a sequence pass through (a sequence keeps one configuration: sequence.h). */
static inline unsigned quality_class_bit(double altitude_km, double sun_elevation_deg)
{
    return 1u << quality_scene_class(altitude_km, sun_elevation_deg);
}
/* "noon", or "sunset+twilight" for a set. */
void quality_class_names(unsigned classes, char *out, size_t size);

/* --max-error: the cheapest configuration whose measured mean relative luminance error is <= max_error on every
 * class of the set (its cost: its dearest class), and whose horizon-band error (the max over the pixels within 2 px
 * of the horizon against the per-pixel march, quality_horizon_table.h) is <= max_error as well (on a class that table
 * covers, a configuration it lacks is refused); NULL if none is (the caller says so). *measured gets its largest (mean) error.
 * The table of the running device's kind, as quality_auto's. */
const quality_config *quality_pick(double max_error, unsigned classes, bool cpu_device, double *measured);

/* --quality auto (the default of a headless render): a point on the measured front, the cheapest measured
 * configuration whose mean error on each class of the set is within max(1 %, 1.25 x the best measured error on
 * that class), in the table of the device kind: GPU (quality_table.h, sky GPU ms on an H200) or CPU
 * (quality_table_cpu.h, CPU ms per whole frame on lavapipe). *measured: as quality_pick. */
/* What a measured table was measured with (issue 31): "<shader key>/<knob hash>", a hash of the sky image's embedded
 * SPIR-V (sky_image_shaders_key: the LUT and sky passes, what the tables measure; not the post chain or the
 * composite) and an FNV-1a hash of the knobs of every configuration its rows name. tools/tradeoff --emit-table
 * records it (QUALITY_TABLE_KEY / QUALITY_TABLE_CPU_KEY); a table measured with other shaders or
 * knobs is re-measured, or its rows are marked as estimates (QUALITY_TABLE_ESTIMATE / ..._CPU_ESTIMATE: why). */
void quality_names_key(const char *const *names, int count, char *out, size_t size);
void quality_table_key(bool cpu_device, char *out, size_t size);   /* this build's key for the compiled-in table */
const char *quality_table_recorded_key(bool cpu_device);            /* the key the table records */
/* NULL when the table was measured with this build's key; else why its rows are only estimates (the table's
 * estimate note, or "measured with other shaders or knobs"). */
const char *quality_table_estimate(bool cpu_device);
#define QUALITY_AUTO_FLOOR 0.01
#define QUALITY_AUTO_SLACK 1.25
const quality_config *quality_auto(unsigned classes, bool cpu_device, double *measured);
/* The colour axis (issue 32 item 5; quality_color_table.h): the measured worst CIEDE2000 of colour setting
 * `wavelengths` (0: RGB, what every preset renders; N: --spectral N) on scene class c against the 48-wavelength
 * spectral reference; INFINITY for a setting the table lacks. quality_color_settings lists the measured settings,
 * fewest wavelengths first (count returned, at most `max`). */
double quality_color_error(int wavelengths, int c);
int quality_color_settings(int *out, int max);
#endif
