/* The LUT cache on disk (see sky/lut_cache.h). */
#include "sky/lut_cache.h"
#include "gpu/pipeline_cache.h"
#include "sky/shaders.h"
#include <stdlib.h>
#include <string.h>

/* Fixed layout, zeroed before it is filled (padding bytes are part of the key's bytes). */
typedef struct lut_cache_key {
    char shaders[32];
    uint32_t vendor, device, driver, format;
    uint8_t uuid[VK_UUID_SIZE];
    int32_t quality[7];          /* sky_lut_quality's sizes and steps that shape the cached LUTs */
    uint32_t widths[3], heights[3];
    sky_variant variant;
    uint64_t medium;             /* sky_atmosphere_lut_hash of the uniform block */
} lut_cache_key;

int sky_lut_cache_images(const sky_renderer *r, const gpu_image *imgs[3], const char *names[3])
{
    int n = 0;
    imgs[n] = &r->luts.transmittance, names[n++] = "transmittance_lut";
    if (r->variant.multiscatter) imgs[n] = &r->luts.multiscatter, names[n++] = "multiscatter_lut";
    if (r->variant.ground) imgs[n] = &r->luts.ground_irradiance, names[n++] = "ground_irradiance_lut";
    return n;
}

static size_t image_bytes(const gpu_image *img)
{
    size_t texel = img->format == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 8;
    return (size_t)img->extent.width * img->extent.height * texel;
}

VkBufferImageCopy sky_lut_cache_region(const gpu_image *img, VkDeviceSize *offset)
{
    VkBufferImageCopy region = {.bufferOffset = *offset, .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {img->extent.width, img->extent.height, 1}};
    *offset += image_bytes(img);
    return region;
}

size_t sky_lut_cache_size(const sky_renderer *r)
{
    const gpu_image *imgs[3];
    const char *names[3];
    size_t bytes = 0;
    for (int i = 0, n = sky_lut_cache_images(r, imgs, names); i < n; ++i) bytes += image_bytes(imgs[i]);
    return bytes;
}

static void make_key(const sky_renderer *r, lut_cache_key *k)
{
    memset(k, 0, sizeof *k);
    strncpy(k->shaders, sky_shaders_key(), sizeof k->shaders - 1);
    const VkPhysicalDeviceProperties *p = &r->ctx->props;
    k->vendor = p->vendorID, k->device = p->deviceID, k->driver = p->driverVersion;
    memcpy(k->uuid, p->pipelineCacheUUID, VK_UUID_SIZE);
    k->format = (uint32_t)r->luts.transmittance.format;
    const sky_lut_quality *q = &r->desc.lut;
    int32_t quality[7] = {q->transmittance_width, q->transmittance_height, q->transmittance_steps,
                          q->multiscatter_size, q->multiscatter_steps, q->multiscatter_sqrt_dirs, q->lut_f32};
    memcpy(k->quality, quality, sizeof quality);
    const gpu_image *imgs[3];
    const char *names[3];
    for (int i = 0, n = sky_lut_cache_images(r, imgs, names); i < n; ++i)
        k->widths[i] = imgs[i]->extent.width, k->heights[i] = imgs[i]->extent.height;
    k->variant = r->variant;
    /* The sun disc is drawn by the sky and composite passes (sky_common.glsl: sun_disc, sky_radiance); the LUT passes'
     * march (sky_march) never reads HAS_SUN_DISC, so a frame without the disc shares the LUTs of one with it (ctest
     * lut_cache part 8: the two computed apart are the same bytes). */
    k->variant.sun_disc = VK_FALSE;
    /* The current medium: at a fetch the LUTs are about to be made for it, at a store they hold it (checked there). */
    k->medium = sky_atmosphere_lut_hash(&r->atmosphere, r->variant.sun_visibility);
}

bool sky_lut_cache_fetch(sky_renderer *r)
{
    const gpu_context *ctx = r->ctx;
    /* At most SKY_LUT_CACHE_FILES_MAX files written per renderer, for the first media it meets (the warm start):
     * every wavelength group of a spectral image, whose groups take turns on one renderer (app/runs/spectral_host.c),
     * while a medium animation, whose every frame computes new LUTs, stops filling the directory after its first
     * frames. Once the budget is spent (or the directory is unwritable) nothing more is looked up either. */
    if (r->lut_cache_files >= SKY_LUT_CACHE_FILES_MAX || r->lut_cache == SKY_LUT_CACHE_UNWRITABLE) return false;
    r->lut_cache = SKY_LUT_CACHE_OFF;
    if (!ctx->cache_file) return false;   /* --no-cache, or no cache directory */
    /* VKSKY_LUT_CACHE=0: the test suite's setting (tests/CMakeLists.txt). Its tests count LUT passes and trace
     * barriers in one shared cache directory, where a test's second run would otherwise differ from its first.
     * VKSKY_LUT_CACHE=ro: read, never write (tests that share LUTs a ctest fixture computed: a reader running
     * beside another never writes the directory, and a miss computes the LUTs as with the cache off). */
    const char *env = getenv("VKSKY_LUT_CACHE");
    if (env && !strcmp(env, "0")) return false;
    bool read_only = env && !strcmp(env, "ro");
    lut_cache_key key;
    make_key(r, &key);
    size_t size = sky_lut_cache_size(r);
    void *payload = gpu_cache_blob_load(ctx, "luts", &key, sizeof key, size);
    if (!payload) {
        r->lut_cache = read_only ? SKY_LUT_CACHE_OFF : SKY_LUT_CACHE_MISS;
        return false;
    }
    /* The staging buffer of an earlier upload was consumed by a submission that has finished (a new atmosphere
     * is set only while no frame is in flight). */
    gpu_buffer_destroy(ctx, &r->lut_staging);
    gpu_buffer_create(ctx, &r->lut_staging, "lut cache staging", size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    memcpy(r->lut_staging.mapped, payload, size);
    free(payload);
    VkMappedMemoryRange range = {.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = r->lut_staging.memory,
                                 .size = VK_WHOLE_SIZE};
    VK_CHECK(vkFlushMappedMemoryRanges(ctx->device, 1, &range));   /* non-coherent memory: host writes to the device */
    r->lut_cache = SKY_LUT_CACHE_HIT;
    return true;
}

void sky_lut_cache_put(sky_renderer *r, const void *payload, size_t size)
{
    lut_cache_key key;
    make_key(r, &key);
    r->lut_cache = gpu_cache_blob_store(r->ctx, "luts", &key, sizeof key, payload, size) ? SKY_LUT_CACHE_STORED
                                                                                         : SKY_LUT_CACHE_UNWRITABLE;
    if (r->lut_cache == SKY_LUT_CACHE_STORED) ++r->lut_cache_files;
}
