/* The device limits the renderer's pipelines need beyond Vulkan 1.3's required minimums (the spec's "Required Limits"
 * table, VkPhysicalDeviceLimits), checked when a context is made or adopted: a device below one is refused with one
 * line naming the limit, the device's value and the need, instead of failing later inside a pipeline's creation. */
#ifndef VKSKY_SKY_LIMITS_H
#define VKSKY_SKY_LIMITS_H
#include <volk.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct sky_limit_needs {
    uint32_t compute_work_group_invocations;     /* maxComputeWorkGroupInvocations */
    uint32_t per_stage_storage_images;           /* maxPerStageDescriptorStorageImages */
    uint32_t compute_shared_memory;              /* maxComputeSharedMemorySize, bytes */
    uint32_t push_constants;                     /* maxPushConstantsSize, bytes */
} sky_limit_needs;

/* What the pipelines need; `single_pass_bloom` (the memory model at device scope enabled: bloom_spd.comp) raises the
 * shared memory need. */
void sky_limits_needed(bool single_pass_bloom, sky_limit_needs *out);
/* 0 if `limits` meet the needs; else -1 and `why` holds one line ("maxComputeWorkGroupInvocations: the device has
 * 128; vksky needs 256 (...)"): the first limit short. */
int sky_limits_check(const VkPhysicalDeviceLimits *limits, bool single_pass_bloom, char *why, size_t why_size);
/* The single-pass bloom's shared memory fits the device (else the per-level chain runs). */
bool sky_limits_single_pass_fits(const VkPhysicalDeviceLimits *limits);
struct gpu_context;
/* A context's device against the needs: the single pass dropped (the per-level chain runs) when its shared memory
 * does not fit, then sky_limits_check. 0, or -1 with the line in `why` (the caller reports it). */
int sky_limits_apply(struct gpu_context *ctx, char *why, size_t why_size);
/* The command line's: sky_limits_apply, its line through gpu_report ("vksky: ..." on stderr); 0 or -1 (exit 1). */
int sky_limits_report(struct gpu_context *ctx);
#endif
