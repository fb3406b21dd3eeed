/* The SCENE_LINEAR pass: vksky's sky and aerial perspective written into a frame the host owns.
 *
 * The host renders its geometry into its own HDR colour image and depth buffer; host_frame_record() records, into
 * the host's command buffer, the LUTs when the atmosphere changed (frame.c), then one compute pass over the host's
 * colour image: where the depth is the far plane the sky along the pixel's ray, elsewhere colour x T + S over the
 * camera -> point segment. The host's images come with how the host used them just before (what vksky waits for)
 * and how it uses them just after (what vksky hands them over to): every barrier on them is recorded here, named,
 * traced and drop-tested (docs/synchronization.md, "A library in a frame it does not own"). */
#ifndef VKSKY_SKY_HOST_FRAME_H
#define VKSKY_SKY_HOST_FRAME_H
#include "sky/renderer.h"
#include "host_frame_push.h"

/* One of the host's images: its handles and its use before and after vksky's (stage, access, layout; `before`
 * layout UNDEFINED: its contents are not needed). Mirrors vksky_image (include/vksky.h). */
typedef struct host_image {
    VkImage image;
    VkImageView view;
    VkFormat format;
    VkExtent2D extent;
    gpu_usage_info before, after;
} host_image;

/* The host's camera (vksky_camera): world metres, +Y up, the ground y = -origin_altitude_m below the world origin;
 * view and projection column-major as GLSL reads them, Vulkan clip space (y down, depth 0..1, reversed or not). */
typedef struct host_camera {
    double position_m[3];
    double origin_altitude_m;
    double view[16];
    double projection[16];
} host_camera;

/* The pass's push constants for a camera, the sun and the march settings of `view` (its camera fields are not
 * read), over a width x height image. Returns 0, or -1 (the message in err) for a projection that is not a
 * perspective (the depth -> point mapping assumes w depends on depth alone) or a camera below the ground. */
int host_frame_push(const host_camera *camera, const sky_view *view, double ground_radius_km,
                    double atmosphere_top_km, uint32_t width, uint32_t height, bool has_depth, HostFramePush *out,
                    char *err, size_t err_size);

#define HOST_FRAME_SETS 8
typedef struct host_frame {
    VkFormat format;                 /* the host colour image's: RGBA16F or RGBA32F */
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorPool pool;
    VkSampler nearest;               /* the depth's (texelFetch) */
    /* One set per (colour, depth) view pair seen, least recently used replaced: a set is never rewritten while a
     * command buffer of one of the last HOST_FRAME_SETS - 1 pairs may be pending (docs/library.md). */
    VkDescriptorSet sets[HOST_FRAME_SETS];
    VkImageView set_color[HOST_FRAME_SETS], set_depth[HOST_FRAME_SETS];
    uint64_t set_used[HOST_FRAME_SETS], use_clock;
} host_frame;

/* Whether the host's colour format can be the pass's storage image. */
bool host_frame_format_supported(VkFormat format);
/* The pass over the renderer's LUTs and scene variant (set them first). Returns 0, or -1 with the message in err. */
int host_frame_create(host_frame *h, sky_renderer *r, VkFormat color_format, char *err, size_t err_size);
void host_frame_destroy(host_frame *h, const sky_renderer *r);

typedef struct host_frame_desc {
    const host_image *color;         /* the HDR image holding the geometry (storage-capable) */
    const host_image *depth;         /* sampled; NULL: sky in every pixel */
    const HostFramePush *push;
    bool force_luts;
} host_frame_desc;
/* The frame, in order, with every barrier (host_frame.c). No allocation, no submission. */
void host_frame_record(sky_renderer *r, host_frame *h, VkCommandBuffer cmd, const host_frame_desc *f);
#endif
