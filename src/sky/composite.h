/* The composite pass: the atmosphere applied to a rendered image (beauty + world position), with AOV layers.
 *
 * Its frame (composite_frame_record, composite.c) reads like frame.c's: the LUTs when the atmosphere changed,
 * the upload of the inputs, the composite dispatch, the readback, with every barrier between them named and
 * traced. The camera and the world's conventions (units, up axis, where the ground is) become the pass's push
 * constants in composite_push(); nothing planet-scale reaches the shader. */
#ifndef VKSKY_SKY_COMPOSITE_H
#define VKSKY_SKY_COMPOSITE_H
#include "sky/ap_volume.h"
#include "sky/renderer.h"

/* The world of the rendered image, its camera and sun. */
typedef struct composite_view {
    double camera[3];               /* camera position, world units */
    double km_per_unit;             /* world unit in km (metres: 0.001) */
    int up_axis;                    /* 1: +Y up, 2: +Z up */
    double ground_altitude_km;      /* altitude of the plane "world up = 0"; the planet's centre straight below
                                       the world origin */
    bool oriented;                  /* the camera's axes are known (else sky pixels keep the beauty) */
    double forward[3], right[3], up[3];   /* camera axes in world coordinates (unit, right-handed: up on screen) */
    double fov_y_deg;               /* vertical field of view */
    double sun_azimuth_deg, sun_elevation_deg;   /* azimuth 0 north: world +Y (Z up) or -Z (Y up), 90 east: +X
                                                    (docs/aerial_perspective.md "Conventions") */
    int steps, max_steps;           /* march steps (Hillaire's growing count when max_steps > steps) */
    double steps_ramp_km, sample_offset, step_distribution;
} composite_view;

/* Camera axes in world coordinates from vksky's yaw/pitch convention (the sky's --yaw/--pitch) turned into the
 * world's axes. */
void composite_view_orient_yaw_pitch(composite_view *v, double yaw_deg, double pitch_deg);

/* World coordinates -> vksky's local frame (north, up, east; same handedness): Z up (x, y, z) -> (y, z, x), Y up
 * (x, y, z) -> (-z, y, x). */
void composite_world_to_local(int up_axis, const double w[3], double out[3]);

/* The push constants of a width x height composite. Returns the camera's altitude in km (negative: the camera
 * is inside the planet, nothing is filled in). */
double composite_push(const composite_view *v, double bottom_radius_km, uint32_t width, uint32_t height,
                      CompositePush *out);

/* The composite's fast defaults (composite.comp, docs/aerial_perspective.md "Cost"): when the march count is fixed by
 * default (no --max-steps: v->max_steps 0), a segment camera -> surface marches a count growing with its length (4
 * steps at 0 km to v->steps at COMPOSITE_POINT_RAMP_KM) and the sky is interpolated across 8x8 tiles where that is
 * exact to 5e-4; flagged by push->march.w < 0 (its ramp). Otherwise the push is left as it is: every pixel marches
 * the given count along its own ray. */
#define COMPOSITE_POINT_RAMP_KM 40.0
void composite_push_fast(const composite_view *v, CompositePush *push);

typedef struct sky_composite {
    uint32_t width, height;
    gpu_image input;                /* RGBA32F, width x 2 height: beauty rows, then position rows */
    gpu_image output;               /* RGBA32F, width x VKSKY_AOV_COUNT height: one band per layer */
    gpu_buffer upload, readback;    /* host-visible: the inputs as uploaded, the layers as read back */
    VkSampler nearest;
    VkDescriptorPool pool;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorSet set;
    bool has_volume;                /* --aerial-perspective volume: the froxel volume, sampled per pixel */
    ap_volume volume;
} sky_composite;

/* Build the pass for images of width x height over the renderer's LUTs (set the renderer's atmosphere and
 * features first: the pipeline carries their variant); `volume` non-NULL: camera -> point from the froxel volume
 * of that shape (ap_volume.h; the push's camera must be oriented), NULL: a march per pixel. Returns 0, or -1 when
 * the device cannot hold the images (the message in err). */
int sky_composite_create(sky_composite *c, sky_renderer *r, uint32_t width, uint32_t height,
                         const ap_volume_desc *volume, char *err, size_t err_size);
void sky_composite_destroy(sky_composite *c, const sky_renderer *r);
/* Where to write the inputs before rendering: width x height RGBA beauty floats, then width x height position
 * floats (xyz, w ignored), top row first. */
float *sky_composite_inputs(sky_composite *c);
/* After rendering: layer k (VKSKY_AOV_*) as width x height RGBA floats. */
const float *sky_composite_layer(const sky_composite *c, int k);

/* The composite frame, in order, with its barriers (composite.c). `follows_frame`: another composite frame was
 * recorded before this one into the same command buffer (VKSKY_FRAMES); its copy wrote the readback buffer. */
void composite_frame_record(sky_renderer *r, sky_composite *c, VkCommandBuffer cmd, const CompositePush *push,
                            bool force_luts, bool follows_frame);
/* Record `frames` frames (tests: VKSKY_FRAMES) into one command buffer, submit, wait, read back. Returns wall
 * milliseconds from submit to fence. */
double sky_composite_render(sky_renderer *r, sky_composite *c, const CompositePush *push, int frames);
#endif
