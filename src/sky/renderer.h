/* The sky renderer's resources and their lifetime: the passes, the frame's images, the atmosphere they are built
 * for; creation, destruction, resizing, new atmosphere or features. frame.c records a frame over them
 * (sky/frame.h), submit.c submits and reads back (sky/submit.h), view_params.c turns a view into push constants. */
#ifndef VKSKY_SKY_RENDERER_H
#define VKSKY_SKY_RENDERER_H
#include "gpu/timing.h"
#include "sky/atmosphere.h"
#include "sky/meter.h"
#include "sky/passes.h"
#include "sky/post.h"
/* The renderer never reads a view; this include gives the renderer's users (options, quality) the view type. */
#include "sky/view_params.h"

typedef struct sky_renderer_desc {
    uint32_t width, height;      /* output size */
    double render_scale;         /* the sky is rendered at this fraction of the output size (0: 1; 1 where the shorter axis would keep < 32 texels), upsampled by the tone map */
    sky_lut_quality lut;         /* LUT sizes, format, steps (zeroed: the defaults) */
    bool bloom;                  /* allocate the bloom chain (no bloom: no passes, no mip chain) */
    uint32_t bloom_mips;         /* downsample passes (0: 5) */
    bool readback;               /* keep the linear composite + display image and copy them to host buffers */
    bool external_display;       /* the tone map writes a frame_target (swapchain), no own display image */
    bool host_storage_tonemap;   /* with external_display and the compute post chain: the compute tone map may write
                                    a frame_target marked storage (a library host's R8G8B8A8_UNORM storage image) */
    VkFormat display_format;     /* the 8-bit target's format (headless: R8G8B8A8_SRGB) */
    post_pass_kind post_pass;    /* bloom + tone map as fragment passes or compute dispatches (auto: by device) */
    bloom_downsample_kind bloom_downsample;  /* compute chain: the downsample in one dispatch, or one per level */
    bool bloom_quarter;          /* the bloom chain starts at a quarter of the HDR size (default: half) */
    /* The first atmosphere and features (NULL: Earth's, the defaults). The pipelines carry the scene's variant:
     * given here they are built once, for it; set after creation, they would be built for Earth first. */
    const model_atmosphere *atmosphere;
    double sun_angular_radius_rad;     /* with atmosphere */
    const sky_features *features;
    bool spectral4;              /* the four-wide spectral build for the renderer's life (--spectral N): SPECTRAL4
                                    shaders, features.fourth packed as a fourth channel, the linear composite the HDR
                                    image's four wavelengths (no bloom, no horizon resolve) */
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
    meter_pass meter;            /* auto exposure's GPU meter (sky/meter.h): its buffer the tone maps read */
    post_pass_kind post_kind;    /* desc.post_pass resolved for the device: fragment or compute */
    sky_renderer_desc desc;
    gpu_image hdr;               /* sky pass output, RGBA16F, render_scale x the output size */
    gpu_image display;           /* tone-mapped, 8-bit (headless) */
    gpu_image composite;         /* HDR + bloom, scene-linear (readback only) */
    /* How the last frame left the display and composite images (readback renderers): the readback copies'
     * GPU_USAGE_TRANSFER_SRC (also before the first frame, whose barriers discard), or after a spectral group's sum
     * (sky/spectral_sum.h) the tone map's write and the sum's sampling; the next frame's barriers start there. */
    gpu_usage display_last, composite_last;
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
    uint64_t lut_hash;           /* of the atmosphere the LUTs hold; 0: never computed */
    bool luts_valid;
    bool hdr_metered;            /* the last frame recorded metered its HDR image (a compute read: the next hdr.to_sky) */
    int variant_builds;          /* times the variant's pipelines were built (--timings) */
    double pipelines_ms;         /* wall time spent making pipelines and the renderer's resources (--timings) */
    /* --async-luts (sky/async_luts.c; the context has a compute queue): */
    bool lut_on_compute_queue;   /* record_luts is filling the compute queue's command buffer */
    bool lut_acquire_pending;    /* the LUTs were released by the compute queue: the next frame's first point owes
                                    the acquire barriers (another queue family only) */
    gpu_timer lut_timer;         /* the LUT passes' timestamps on the compute queue */
    /* The LUT cache on disk (sky/lut_cache.h): what happened to the last LUTs made, and the upload's host copy. */
    enum { SKY_LUT_CACHE_OFF, SKY_LUT_CACHE_HIT, SKY_LUT_CACHE_MISS, SKY_LUT_CACHE_STORED, SKY_LUT_CACHE_UNWRITABLE }
        lut_cache;
    int lut_cache_files;         /* LUT cache files this renderer wrote (at most SKY_LUT_CACHE_FILES_MAX) */
    gpu_buffer lut_staging;
} sky_renderer;

void sky_renderer_create(sky_renderer *r, gpu_context *ctx, const sky_renderer_desc *desc);
void sky_renderer_destroy(sky_renderer *r);
/* Set the atmosphere (writes the uniform buffer: call only while no frame is in flight). LUTs are recomputed
 * by the next frame if their inputs changed. */
void sky_renderer_set_atmosphere(sky_renderer *r, const model_atmosphere *a, double sun_angular_radius_rad);
/* Ground albedo, Mie phase model, limb darkening, sun disc, multi-scattering. A change of what the scene needs
 * (species present, multi-scattering, disc, ground, phase model) rebuilds the pipelines for the new variant. */
void sky_renderer_set_features(sky_renderer *r, const sky_features *f);
/* Both at once (the variant is built at most once, for the new pair): what a new scene calls. */
void sky_renderer_set_scene(sky_renderer *r, const model_atmosphere *a, double sun_angular_radius_rad,
                            const sky_features *f);
/* The LUTs do not hold the current atmosphere (the next frame recomputes them). */
bool sky_renderer_luts_dirty(const sky_renderer *r);
/* New size: rebuilds the HDR target, the bloom mip chain and the tone map's descriptors (waits for the GPU). */
void sky_renderer_resize(sky_renderer *r, uint32_t width, uint32_t height);

#endif
