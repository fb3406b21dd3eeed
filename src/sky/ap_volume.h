/* Hillaire's aerial-perspective volume (issue 12 item 2, --aerial-perspective volume): a camera-frustum froxel
 * volume of transmittance and in-scattering, built once per frame by a compute pass (ap_volume.comp, the march of
 * aerial.glsl once per froxel) and sampled by the composite pass per pixel instead of a march per pixel.
 *
 * Layout (docs/aerial_perspective.md): one RGBA16F 3D image of width x height x 3 depth texels, three bands of
 * `depth` slices: per-channel transmittance, the Rayleigh layer, the Mie layer (the composite's AOVs need all
 * nine numbers; one image: one barrier per hazard). Columns cover the composite's frustum (the camera's ray
 * matrix); slice k holds camera -> ap distance range ((k + 1) / depth)^distribution km along its column's ray.
 * Points the volume does not hold (behind, outside the frustum, beyond the range) are marched per pixel.
 * The frame that records it and its barriers: composite_frame_record (composite.c). */
#ifndef VKSKY_SKY_AP_VOLUME_H
#define VKSKY_SKY_AP_VOLUME_H
#include "sky/renderer.h"

typedef struct ap_volume_desc {
    uint32_t width, height, depth;  /* froxels across, down, and slices (default 32 x 32 x 32) */
    float range_km;                 /* the last slice's distance (default 32 km) */
    float distribution;             /* slice spacing exponent: 1 linear, 2 quadratic (Hillaire; the default) */
} ap_volume_desc;

ap_volume_desc ap_volume_desc_default(void);

/* The renderer's specialization constants plus the volume's range and distribution (VKSKY_SPEC_AP_*): for the
 * volume's build pipeline and the composite's volume variant. */
typedef struct ap_volume_spec {
    VkSpecializationMapEntry entries[VKSKY_SPEC_COUNT + 2];
    unsigned char data[256];
    VkSpecializationInfo info;
} ap_volume_spec;
void ap_volume_spec_make(const VkSpecializationInfo *base, const ap_volume_desc *d, ap_volume_spec *out);

typedef struct ap_volume {
    ap_volume_desc desc;
    gpu_image image;                /* RGBA16F, width x height x 3 depth: bands T, rayleigh, mie */
    VkDescriptorPool pool;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorSet set;
} ap_volume;

/* 0, or -1 with the reason in err (a size out of range, or more than the device's 3D images hold). */
int ap_volume_create(ap_volume *a, sky_renderer *r, const ap_volume_desc *d, char *err, size_t err_size);
void ap_volume_destroy(ap_volume *a, const sky_renderer *r);
/* The build dispatch alone (the image in GENERAL, the LUTs readable); the caller records the barriers. */
void ap_volume_dispatch(const ap_volume *a, VkCommandBuffer cmd, const CompositePush *push);
#endif
