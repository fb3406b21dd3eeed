/* The options struct alone: everything one run is asked to do, as the flags (app/options) and a scene file
 * (app/scene) fill it in. Header-only (types, no calls), so that the flag parser and the scene loader both write it
 * without either including the other. Include app/cli/options.h for the parser and the helpers that read it. */
#ifndef VKSKY_APP_OPTIONS_STRUCT_H
#define VKSKY_APP_OPTIONS_STRUCT_H
#include "app/scene/sun_place.h"
#include "model/medium.h"
#include "model/spectral_medium.h"
#include "sky/renderer.h"
#include <stdbool.h>

#define OPTIONS_MAX_OUTPUTS 4
#define OPTIONS_MAX_ANIMATE 16
#define OPTIONS_UNITS_PHOTOMETRIC 0   /* pixels in cd/m2 (Y), the sun from the solar spectrum (app/scene/light.c) */
#define OPTIONS_UNITS_RELATIVE 1      /* the lesson's scale: the sun 20,20,20, exposure in stops */
#define OPTIONS_EXR_AUTO 0            /* float where a value would overflow half (the sun's disc), else half */
#define OPTIONS_EXR_HALF 1
#define OPTIONS_EXR_FLOAT 2

/* One flag of the command line as a value (issue 25: F5 applies them again over a scene file read again, without
 * parsing the command line again): the flag, its text (words, names, paths: what the flag's value is), and for a
 * numeric flag its number, parsed once where the parse applied it. */
#define OPTIONS_MAX_GIVEN 256
typedef struct options_given {
    const struct flag *flag;                    /* app/cli/flags.h */
    const char *text;                           /* NULL for a flag without a value */
    double number;                              /* a numeric flag's value, once parsed */
    bool parsed;
} options_given;

/* One --animate PARAM=FROM:TO: a numeric flag (or "time": the local clock, decimal hours) going linearly from FROM at
 * the sequence's first frame to TO at its last. */
typedef struct options_animation {
    const char *flag_name;                      /* "--sun-elevation", ...; "--time" for time (hours) */
    bool integer;                               /* an integer flag: the value is rounded */
    double from, to;
} options_animation;

typedef struct options {
    sky_view view;
    int width, height;
    sky_lut_quality lut;                        /* LUT sizes, steps, format */
    model_atmosphere atmosphere;                  /* the medium (Hillaire Table 1 unless flags change it) */
    bool reference;                             /* --reference: CPU ground truth instead of the GPU */
    bool path_trace;                            /* --path-trace: the Monte Carlo path tracer as the ground truth */
    int path_samples;                           /* paths per pixel / direction */
    int spectral;                               /* --spectral N: the reference's wavelengths (0: RGB) */
    bool spectral_medium_set;                   /* the scene's "spectral" section gave the medium per wavelength */
    spectral_medium spectral_medium;            /* that medium (else the RGB medium's, spectral_medium_from_rgb) */
    double max_color_error;                     /* --max-color-error DE (0: off): picks --spectral (issue 32) */
    bool irradiance;                            /* --irradiance: irradiance at the camera (with --reference) */
    double tilt_deg, tilt_azimuth_deg;          /* --tilt, --tilt-azimuth: the tilted surface of --irradiance */
    bool tilt_azimuth_set;
    double scales[3];
    const char *quality;                        /* --quality preset name (NULL: none) */
    bool quality_auto;                          /* the knobs are --quality auto's choice (named or the default) */
    unsigned quality_classes;                   /* the scene classes that choice (or --max-error's) served */
    bool quality_cpu_device;                    /* auto's tables were the CPU device's (lavapipe): its colour rule */
    /* Scene features (scene files and their flags). */
    const char *scene_path;                     /* --scene FILE.json (NULL: none) */
    bool scene_quality;                         /* the scene file has a quality section (no --quality auto then) */
    bool dump_scene;                            /* --dump-scene: print the effective scene as JSON and exit */
    double ground_albedo[3];                    /* --ground-albedo R,G,B (default 0) */
    int mie_phase;                              /* 0 Henyey-Greenstein, 1 Cornette-Shanks (--mie-phase) */
    double sun_angular_radius_deg;              /* --sun-angular-radius (default 0.265) */
    double limb_darkening;                      /* sun limb darkening coefficient u (default 0.6) */
    bool sun_disc;                              /* draw the sun disc (default true) */
    bool multiple_scattering;                   /* the multi-scattering term and LUT (default true) */
    bool trace_passes;                          /* --trace-passes: list the passes a frame recorded */
    double max_error;                           /* --max-error (0: off) */                           /* density scales given so far: Rayleigh, Mie, ozone */
    double render_scale;
    int bloom_mips;
    post_pass_kind post_pass;                   /* --post-pass: bloom + tone map as draws or dispatches (default auto) */
    bloom_downsample_kind bloom_downsample;     /* --bloom-downsample: the compute chain's downsample */
    bool bloom_quarter;                         /* --bloom-res quarter: the bloom chain from a quarter-size mip 0 */
    const char *outputs[OPTIONS_MAX_OUTPUTS];   /* --render, .exr or .png */
    int output_count;
    int bench_frames;                           /* --bench N (0: off) */
    int frames;                                 /* window: quit after N presented frames (0: run until closed) */
    const char *screenshot;                     /* window: save the last presented image (.png) before quitting */
    bool validate;
    bool async_luts;                            /* --async-luts: the LUT passes on a compute queue */
    bool list_devices;
    int device_index;                           /* -1: pick */
    bool trace_barriers;
    bool quiet;                                 /* --quiet: no progress on stderr */
    bool help, version;
    /* tooling (issue 14) */
    sun_place place;                            /* --date, --time, ... or the scene's sun.date ...: the sun by SPA */
    const char *sun_angles_flag;                /* --sun-elevation or --sun-azimuth on the command line (NULL: neither) */
    bool sun_elevation_flag, sun_azimuth_flag;  /* which of them */
    bool list_scenes;                           /* --list-scenes */
    /* sequences (issue 14): app/cli/options_sequence.c, app/runs/sequence.c */
    options_animation animate[OPTIONS_MAX_ANIMATE];
    int animate_count;
    int frame_count;                            /* --frame-count N (default 1) */
    int frame_first, frame_last;                /* --frame-range A:B, inclusive (default 0 : N-1) */
    bool frame_range_set;
    bool skip_existing;                         /* --skip-existing: frames already written whole are kept (resume) */
    /* throughput (issue 27): app/cli/options_throughput.c */
    int threads;                                /* --threads N: EXR encode threads (0: the cores available) */
    int exr_compression;                        /* --exr-compression: exr_compression_t + 1 (0: not given, ZIP) */
    int zip_level;                              /* --exr-compression zip:N: deflate level (0: the default, 4) */
    int argc;                                   /* the command line: a frame's options re-parse it, EXRs record it */
    char **argv;
    /* physical light (issue 32): app/scene/light.c */
    int units;                                  /* OPTIONS_UNITS_PHOTOMETRIC (default) or OPTIONS_UNITS_RELATIVE */
    int exr_type;                               /* OPTIONS_EXR_AUTO (default), OPTIONS_EXR_HALF, OPTIONS_EXR_FLOAT */
    bool exposure_given;                        /* --exposure or the scene's output.exposure_ev100: EV100 fixed */
    double exposure_ev100;                      /* that EV100 (photometric units; app/scene/light.c applies it) */
    double exposure_stops;                      /* the lesson's exposure (scene output.exposure_ev), kept for dumps
                                                   once view.exposure_ev holds EV100 (light_finish) */
    bool auto_exposure;                         /* --auto-exposure (photometric PNGs and the window: the default) */
    /* start-up (issue 27): app/runs/startup.c */
    bool no_cache;                              /* --no-cache: no pipeline cache on disk (read or written) */
    bool timings;                               /* --timings: where the first image's time went, on stderr */
    /* sequences (issue 25): the options as the flags and scene left them, before the derived steps (malloc'd by the
     * parse when something is animated; options_release): each frame sets its animated values there and finishes */
    struct options *unresolved;
    /* F5 (issue 25): the command line's flags as values, in their order (options_reload) */
    options_given given[OPTIONS_MAX_GIVEN];
    int given_count;
} options;
#endif
