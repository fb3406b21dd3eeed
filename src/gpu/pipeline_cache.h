/* A Vulkan pipeline cache kept on disk between runs, one file per device and driver (issue 27).
 *
 * The file is <dir>/pipelines-<device UUID>-<driver version>.bin: a small header of ours (magic, the build's shader
 * key, the data's size and checksum) and then the driver's cache data as vkGetPipelineCacheData returned it. Before
 * the driver sees a byte of it, the file must be whole (size and checksum), from this build (the key: otherwise it
 * is replaced quietly) and for this device: the data's VkPipelineCacheHeaderVersionOne must name the device's
 * vendor, device and pipelineCacheUUID. A file that fails is ignored with one note on stderr and replaced when the
 * run ends. Saving writes a temporary file beside the target and renames it over (readers never see half a file);
 * a directory that cannot be made or written costs one note and nothing else. Knows nothing of skies. */
#ifndef VKSKY_GPU_PIPELINE_CACHE_H
#define VKSKY_GPU_PIPELINE_CACHE_H
#include "gpu/context.h"

/* Creates ctx->pipeline_cache, seeded from dir's file when that file passes the checks. dir NULL: no file (the
 * cache still serves the pipelines of this run). build_key: a short text that changes whenever the shaders do. */
void gpu_pipeline_cache_open(gpu_context *ctx, const char *dir, const char *build_key);
/* Writes the cache back if it holds more than was read, then destroys it. Called by gpu_context_destroy. */
void gpu_pipeline_cache_close(gpu_context *ctx);
/* The keyed blobs' home (the LUT cache) for a context with no pipeline cache file of vksky's (an adopted device:
 * vksky_context_set_cache_directory); NULL detaches it. False: the path is too long. Never saves a pipeline cache. */
bool gpu_cache_dir_attach(gpu_context *ctx, const char *dir);
/* The directory of the context's cache files, or NULL (--no-cache, none attached). */
const char *gpu_cache_dir(const gpu_context *ctx);

/* The checks on a file's bytes, for tests: NULL if `file` may seed the cache of the device `props`, else why not
 * ("truncated", "corrupt (checksum)", "not a vksky pipeline cache", "from another build", "made for another device
 * or driver", ...). */
const char *gpu_pipeline_cache_check(const unsigned char *file, size_t size, const char *build_key,
                                     const VkPhysicalDeviceProperties *props);

/* Keyed blobs in the same directory (the LUT cache): NULL where the context has no cache directory (--no-cache).
 * load: the payload (malloc'd, payload_size bytes) of the file stored under `key` for this device and driver, or
 * NULL: absent (silently), or failing the checks (magic, version, sizes, checksum, the key byte for byte, the
 * payload's size: one note, and the caller recomputes and stores over it). store: written atomically (temporary
 * file, rename); false and one note when it cannot be. */
void *gpu_cache_blob_load(const gpu_context *ctx, const char *name, const void *key, size_t key_size,
                          size_t payload_size);
bool gpu_cache_blob_store(const gpu_context *ctx, const char *name, const void *key, size_t key_size,
                          const void *payload, size_t payload_size);
/* The checks on a blob file's bytes (for tests): NULL if it holds `key` and a payload of payload_size, else why not. */
const char *gpu_cache_blob_check(const unsigned char *file, size_t size, const void *key, size_t key_size,
                                 size_t payload_size);
#endif
