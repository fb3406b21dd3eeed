/* The options struct alone: everything one run is asked to do, as the flags (app/options) and a scene file
 * (app/scene) fill it in. Header-only (types, no calls), so that the flag parser and the scene loader both write it
 * without either including the other. Include app/options.h for the parser and the helpers that read it. */
#ifndef VKSKY_APP_OPTIONS_STRUCT_H
#define VKSKY_APP_OPTIONS_STRUCT_H
#include "model/medium.h"
#include "sky/renderer.h"
#include <stdbool.h>

#define OPTIONS_MAX_OUTPUTS 4

typedef struct options {
    sky_view view;
    int width, height;
    sky_lut_quality lut;                        /* LUT sizes, steps, format */
    model_atmosphere atmosphere;                  /* the medium (Hillaire Table 1 unless flags change it) */
    bool reference;                             /* --reference: CPU ground truth instead of the GPU */
    bool path_trace;                            /* --path-trace: the Monte Carlo path tracer as the ground truth */
    int path_samples;                           /* paths per pixel / direction */
    double scales[3];
    const char *quality;                        /* --quality preset name (NULL: none) */
    /* Scene features (scene files and their flags). */
    const char *scene_path;                     /* --scene FILE.json (NULL: none) */
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
    const char *outputs[OPTIONS_MAX_OUTPUTS];   /* --render, .exr or .png */
    int output_count;
    int bench_frames;                           /* --bench N (0: off) */
    int frames;                                 /* window: quit after N presented frames (0: run until closed) */
    const char *screenshot;                     /* window: save the last presented image (.png) before quitting */
    bool validate;
    bool list_devices;
    int device_index;                           /* -1: pick */
    bool trace_barriers;
    bool quiet;                                 /* --quiet: no progress on stderr */
    bool help, version;
} options;
#endif
