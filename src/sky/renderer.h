/* The sky renderer: owns the passes and the frame's images; frame.c records a frame over them. */
#ifndef VKSKY_SKY_RENDERER_H
#define VKSKY_SKY_RENDERER_H
#include "gpu/timing.h"
#include "sky/atmosphere.h"
#include "sky/passes.h"
#include "sky/post.h"

typedef enum sky_mode_choice { SKY_CHOICE_MARCH, SKY_CHOICE_SKYVIEW, SKY_CHOICE_AUTO, SKY_CHOICE_FILL } sky_mode_choice;

typedef struct sky_view {
    double altitude_km;                     /* camera altitude above the ground, >= 0 */
    double yaw_deg, pitch_deg, fov_deg;     /* view axis: same convention as the sun's azimuth/elevation */
    double sun_azimuth_deg, sun_elevation_deg;
    int steps;                              /* view march steps (the minimum when max_steps > steps) */
    int max_steps;                          /* > steps: Hillaire's variable count, growing with path length (0: fixed) */
    double steps_ramp_km;                   /* path length at which the variable count reaches max_steps */
    double sample_offset;                   /* sample position within a step: 0.5 midpoint, 0.3 Hillaire */
    double step_distribution;               /* step ends at t_max (i/N)^p: 1 uniform, 2 quadratic (Hillaire) */
    sky_mode_choice mode;                   /* per-pixel march, sky-view LUT lookup, or auto */
    sky_pass_kind pass_kind;                /* fragment or compute sky pass */
    int skyview_steps;                      /* march steps of the sky-view LUT texels */
    double exposure_ev;                     /* tone map exposure, in stops */
    int tonemap;                            /* VKSKY_TONEMAP_* */
    bool bloom;
    double bloom_strength, bloom_threshold;
} sky_view;

sky_view sky_view_default(void);

typedef struct sky_renderer_desc {
    uint32_t width, height;      /* output size */
    double render_scale;         /* the sky is rendered at this fraction of the output size (0: 1), upsampled by the tone map */
    sky_lut_quality lut;         /* LUT sizes, format, steps (zeroed: the defaults) */
    bool bloom;                  /* allocate the bloom chain (no bloom: no passes, no mip chain) */
    uint32_t bloom_mips;         /* downsample passes (0: 5) */
    bool readback;               /* keep the linear composite + display image and copy them to host buffers */
    bool external_display;       /* the tone map writes a frame_target (swapchain), no own display image */
    VkFormat display_format;     /* the 8-bit target's format (headless: R8G8B8A8_SRGB) */
    post_pass_kind post_pass;    /* bloom + tone map as fragment passes or compute dispatches (auto: by device) */
    bloom_downsample_kind bloom_downsample;  /* compute chain: the downsample in one dispatch, or one per level */
    bool bloom_quarter;          /* the bloom chain starts at a quarter of the HDR size (default: half) */
} sky_renderer_desc;

typedef struct sky_renderer {
    gpu_context *ctx;
    pass_shared shared;
    VkDescriptorPool size_pool;  /* descriptor sets of the size-dependent passes (bloom, tone map) */
    sky_luts luts;
    sky_pass sky;
    bloom_chain bloom;
    tonemap_pass tonemap;
    post_compute post;           /* the compute post chain (post_kind compute) */
    post_pass_kind post_kind;    /* desc.post_pass resolved for the device: fragment or compute */
    sky_renderer_desc desc;
    gpu_image hdr;               /* sky pass output, RGBA16F, render_scale x the output size */
    gpu_image display;           /* tone-mapped, 8-bit (headless) */
    gpu_image composite;         /* HDR + bloom, scene-linear (readback only) */
    gpu_buffer readback_linear, readback_display;
    gpu_timer timer;
    gpu_timer *active_timer;     /* the timer of the frame being recorded */
    AtmosphereParams atmosphere;
    model_atmosphere medium;       /* as last set */
    double sun_angular_radius;
    sky_features features;
    sky_variant variant;         /* of the pipelines built now */
    VkSpecializationMapEntry spec_entries[VKSKY_SPEC_COUNT];
    VkSpecializationInfo spec;
    FILE *pass_trace;            /* non-NULL: print "pass <name>" for every pass a frame records */
    uint64_t lut_hash;           /* of the atmosphere the LUTs hold; 0: never computed */
    bool luts_valid;
} sky_renderer;

void sky_renderer_create(sky_renderer *r, gpu_context *ctx, const sky_renderer_desc *desc);
void sky_renderer_destroy(sky_renderer *r);
/* Set the atmosphere (writes the uniform buffer: call only while no frame is in flight). LUTs are recomputed
 * by the next frame if their inputs changed. */
void sky_renderer_set_atmosphere(sky_renderer *r, const model_atmosphere *a, double sun_angular_radius_rad);
/* Ground albedo, Mie phase model, limb darkening, sun disc, multi-scattering. A change of what the scene needs
 * (species present, multi-scattering, disc, ground, phase model) rebuilds the pipelines for the new variant. */
void sky_renderer_set_features(sky_renderer *r, const sky_features *f);
/* The sky pass kind a frame of this view uses (auto resolved for the device). */
sky_pass_kind sky_renderer_pass_kind(const sky_renderer *r, const sky_view *v);
/* The sky mode a frame of this view uses (auto: the sky-view LUT inside the atmosphere, the march from space). */
sky_mode sky_view_resolve_mode(const sky_view *v, const sky_renderer *r);
bool sky_renderer_luts_dirty(const sky_renderer *r);
/* New size: rebuilds the HDR target, the bloom mip chain and the tone map's descriptors (waits for the GPU). */
void sky_renderer_resize(sky_renderer *r, uint32_t width, uint32_t height);

/* Camera + sun -> the sky pass's push constants (the ray matrix built from the camera basis). */
SkyPush sky_view_push(const sky_view *v, uint32_t width, uint32_t height);
/* The sky-view LUT pass's push constants (its own march settings). */
SkyPush sky_view_skyview_push(const sky_view *v);
TonemapPush sky_view_tonemap_push(const sky_view *v, bool encode_srgb_in_shader);

/* An image the tone map writes that the renderer does not own (a swapchain image). */
typedef struct frame_target {
    VkImage image;
    VkImageView view;
    VkExtent2D extent;
    gpu_usage before;            /* GPU_USAGE_ACQUIRED for a swapchain image */
    gpu_usage after;             /* GPU_USAGE_PRESENT for a swapchain image */
    gpu_buffer *capture;         /* non-NULL: also copy the image into this host buffer (4 bytes a pixel) */
} frame_target;

/* frame.c: the whole frame, in order, with every barrier between the passes. */
typedef struct frame_desc {
    const sky_view *view;
    bool force_luts;             /* recompute the LUTs even if they are up to date (benchmarks) */
    const frame_target *target;  /* NULL: the renderer's own display image (headless) */
    gpu_timer *timer;            /* NULL: the renderer's timer (one per frame in flight otherwise) */
} frame_desc;
void frame_record(sky_renderer *r, VkCommandBuffer cmd, const frame_desc *f);

/* Records a frame, submits it, waits. Returns wall milliseconds from submit to fence. */
double sky_renderer_render(sky_renderer *r, const frame_desc *f);
/* Copy a LUT to the host as floats RGBA (tests): which 0 transmittance, 1 multiscatter; rgba_out holds
 * 4 x the extent's pixels. */
VkExtent2D sky_renderer_lut_extent(const sky_renderer *r, int which);
void sky_renderer_read_lut(sky_renderer *r, int which, float *rgba_out);
#endif
