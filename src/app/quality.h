/* Quality configurations: the speed/accuracy knobs as one value, the four presets, the scene classes of the
 * trade-off measurement, and the measured table --max-error chooses from. */
#ifndef VKSKY_APP_QUALITY_H
#define VKSKY_APP_QUALITY_H
#include "sky/renderer.h"

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
} quality_config;

/* low, medium, high, ultra, lesson (NULL if unknown; "auto" is not a fixed configuration: quality_auto). */
const quality_config *quality_preset(const char *name);
extern const quality_config quality_presets[4];
/* The lesson's configuration (the defaults before --quality auto: the 32-step march, the lesson's LUTs), kept
 * for comparison and for the guide: --quality lesson. The same knobs as the sweep's "march32". */
extern const quality_config quality_lesson;
/* The configurations tools/tradeoff sweeps (presets included). */
extern const quality_config quality_sweep[];
extern const int quality_sweep_count;

/* Apply a configuration's knobs to a view and a renderer description. */
void quality_apply(const quality_config *q, sky_view *v, sky_lut_quality *lut, double *render_scale, int *bloom_mips);

/* The scene set of the trade-off measurement. */
typedef struct quality_scene {
    const char *name;
    double altitude_km, sun_elevation_deg, yaw_deg, pitch_deg, fov_deg, exposure_ev;
} quality_scene;
extern const quality_scene quality_scenes[6];
/* The scene class a view belongs to (nearest by sun elevation and altitude). */
int quality_scene_class(double altitude_km, double sun_elevation_deg);

/* --max-error: the cheapest configuration whose measured mean relative luminance error on the view's scene
 * class is <= max_error; NULL if none is (the caller says so). *measured gets that error. */
const quality_config *quality_pick(double max_error, double altitude_km, double sun_elevation_deg, double *measured,
                                   const char **scene_name);

/* --quality auto (the default of a headless render): a point on the measured front for the view's scene class,
 * the cheapest measured configuration whose mean error is within max(1 %, 1.25 x the best measured error on
 * that class). *measured, *scene_name: as quality_pick. */
#define QUALITY_AUTO_FLOOR 0.01
#define QUALITY_AUTO_SLACK 1.25
const quality_config *quality_auto(double altitude_km, double sun_elevation_deg, double *measured,
                                   const char **scene_name);
#endif
