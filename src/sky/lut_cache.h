/* The LUT cache on disk (issue 27): the LUTs that depend only on the medium (transmittance, multi-scattering and,
 * with a lit ground, the ground irradiance) kept beside the pipeline cache, so that a warm start uploads them
 * instead of computing them (on lavapipe they are most of a small render's time). The sky-view LUT depends on the
 * sun and the camera: it is rendered every frame, never cached.
 *
 * The key is everything the cached LUTs depend on: the build's shader key, the device (vendor, device,
 * pipelineCacheUUID, driver version), the LUT sizes, format and step counts (sky_lut_quality), the pipeline variant
 * (its specialization constants) and the medium as the uniform block holds it (the LUT-relevant part's hash, the
 * renderer's own definition of "the LUTs are stale"). The file's rules are the pipeline cache's
 * (gpu_cache_blob_*: magic, version, sizes, checksum, key; one note for a bad file, atomic writes, one note when
 * it cannot be written). Without a cache directory (--no-cache) nothing is read or written. */
#ifndef VKSKY_SKY_LUT_CACHE_H
#define VKSKY_SKY_LUT_CACHE_H
#include "sky/renderer.h"

/* The most LUT files one renderer writes: a spectral image's wavelength groups, which may all take turns on one
 * renderer (48 wavelengths three to a pass: 16 groups). */
#define SKY_LUT_CACHE_FILES_MAX 16

/* Called when the LUTs are about to be computed: true if the cache holds them, now in r->lut_staging (host memory,
 * flushed) for frame_record_lut_cache_upload. False: compute them, and (with a cache directory) the renderer marks
 * them to be stored after the frame (r->lut_cache == SKY_LUT_CACHE_MISS). */
bool sky_lut_cache_fetch(sky_renderer *r);
/* The bytes of the cached LUTs, in the order transmittance, multi-scattering, ground irradiance (those present). */
size_t sky_lut_cache_size(const sky_renderer *r);
/* After the frame that computed the LUTs and a readback of them (sky_renderer_store_luts): write the file. */
void sky_lut_cache_put(sky_renderer *r, const void *payload, size_t size);
/* The cached LUTs of this variant in the file's order (imgs), with their trace names; returns how many (1-3). */
int sky_lut_cache_images(const sky_renderer *r, const gpu_image *imgs[3], const char *names[3]);
/* The copy region of `img` at *offset in the file's payload; advances *offset past it. */
VkBufferImageCopy sky_lut_cache_region(const gpu_image *img, VkDeviceSize *offset);
#endif
