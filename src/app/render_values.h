/* The values a renderer is built from and set to, made from the parsed options in one place: the scene as the
 * renderer takes it (the medium with the sun in the HDR image's units, the sun's size, the features) and the quality
 * configuration (LUT sizes, render scale, the post chain). Every renderer build (headless, bands, the composite, the
 * window) takes both, so no path drops a knob (--post-pass, --bloom-res) the others honour. */
#ifndef VKSKY_APP_RENDER_VALUES_H
#define VKSKY_APP_RENDER_VALUES_H
#include "app/options_struct.h"
#include "sky/renderer.h"

typedef struct render_scene {
    model_atmosphere atmosphere;   /* the sun in the HDR image's units (app/light.h) */
    double sun_radius_rad;
    sky_features features;
} render_scene;

typedef struct render_quality {
    sky_lut_quality lut;
    double render_scale;
    int bloom_mips;
    post_pass_kind post_pass;
    bloom_downsample_kind bloom_downsample;
    bool bloom_quarter;
} render_quality;

/* Zeroed first, so that two scenes compare bytewise (a sequence drains its ring only on a real change). */
void render_scene_of(const options *o, render_scene *out);
render_quality render_quality_of(const options *o);
/* A description with the quality and the first scene filled in (the pipelines built once, for that scene); the caller
 * adds size, bloom, readback and display. s must outlive sky_renderer_create. */
sky_renderer_desc render_desc(const render_quality *q, const render_scene *s);
/* A new scene for a live renderer (no frame in flight): the variant is rebuilt at most once. */
void render_scene_set(sky_renderer *r, const render_scene *s);
#endif
