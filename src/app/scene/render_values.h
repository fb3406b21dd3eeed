/* The values a run is made of, from the parsed options in one place: the quality configuration (LUT sizes, render
 * scale, the post chain; every renderer build takes it, so no path drops a knob such as --post-pass or --bloom-res the
 * others honour) and what a scene file gives (scene, camera, job), which the CLI and the library's loader share. */
#ifndef VKSKY_APP_RENDER_VALUES_H
#define VKSKY_APP_RENDER_VALUES_H
#include "app/cli/options_struct.h"
#include "sky/renderer.h"

/* The quality configuration: every knob that trades speed for accuracy, as one value (a preset by name, --max-error's
 * pick, a scene's quality section, the flags over them). */
typedef struct render_quality {
    /* the view's march */
    sky_mode_choice mode;
    sky_pass_kind pass_kind;
    int steps, max_steps, skyview_steps;
    double steps_ramp_km, sample_offset, step_distribution;
    /* the renderer's LUTs, scale and post chain */
    sky_lut_quality lut;
    double render_scale;
    int bloom_mips;
    post_pass_kind post_pass;
    bloom_downsample_kind bloom_downsample;
    bool bloom_quarter;
} render_quality;

/* The scene as a file gives it (what vksky_scene holds): planet and medium (the sun in the scene's own units), the
 * features, the sun's place and size. */
typedef struct scene_value {
    model_atmosphere atmosphere;
    double ground_albedo[3];
    int mie_phase;                 /* 0 Henyey-Greenstein, 1 Cornette-Shanks */
    double sun_angular_radius_deg, limb_darkening;
    bool sun_disc, multiple_scattering;
    double sun_elevation_deg, sun_azimuth_deg;
    int units;                     /* OPTIONS_UNITS_* */
} scene_value;

/* Where the camera is and where it looks, on the scene's planet. */
typedef struct camera_value {
    double altitude_km, yaw_deg, pitch_deg, fov_deg;
    double ground_radius_km;       /* the scene's planet (the window's fly camera, app/window/camera.h) */
} camera_value;

/* What a run of the CLI was asked to make: its files and their encoding, the image, the exposure, the frames. */
typedef struct job_value {
    const char *outputs[OPTIONS_MAX_OUTPUTS];
    int output_count;
    int width, height, projection;
    double exposure_ev;            /* EV100 (photometric) or stops */
    bool auto_exposure;
    int tonemap;
    bool bloom;
    int exr_type, exr_compression, zip_level, threads;
    int frame_count, frame_first, frame_last;
    bool skip_existing;
} job_value;

/* The four values of parsed options (any of the out pointers may be NULL). */
void values_of(const options *o, scene_value *scene, camera_value *camera, render_quality *quality, job_value *job);
/* Loaders the CLI and the library share. A scene by file (JSON, or a vksky EXR's vksky:scene) or shipped name, with
 * the camera, quality and job fields the file has (the rest: the defaults of a headless render, quality "lesson"'s
 * knobs until a preset is named). 0 ok; 2 bad input (one line on stderr). */
int values_load_scene(const char *path_or_name, scene_value *scene, camera_value *camera, render_quality *quality,
                      job_value *job);
/* A preset by name (low, medium, high, ultra, lesson, cpu). 0 ok; 2 unknown (nothing printed). */
int values_quality_preset(const char *name, render_quality *out);
/* --max-error's pick for a set of scene classes from the table of a CPU or a GPU device (app/quality/quality.h). 0 ok (*measured: its error); 2 none reaches it. */
int values_quality_pick(double max_error, unsigned classes, bool cpu_device, render_quality *out, double *measured);
/* A quality's march settings onto a view. */
void render_quality_to_view(const render_quality *q, sky_view *v);

/* The options' quality knobs as one value. */
render_quality render_quality_of(const options *o);
#endif
