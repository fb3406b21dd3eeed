/* The device limits the pipelines need (sky/limits.h). Each figure is derived from the shader or the layout that sets
 * it; tests/api/api_limits.c checks them against the SPIR-V the build compiled, and the check against the spec's
 * minimums. */
#include "sky/limits.h"
#include "sky/passes.h"
#include "gpu/context.h"
#include "shared.h"
#include "host_frame_push.h"
#include <stdio.h>

/* bloom_spd.comp's workgroup memory: uint region[REGION * REGION * 3] (REGION 44), uint stack[STACK] (STACK 256),
 * uint stack_size. The largest of the others is multiscatter_lut.comp's (THREADS 64: two spectrum_t arrays, one
 * float array, two vec4 arrays: 4,352 bytes with vec4 spectra), under the spec's 16,384. */
enum { SPD_REGION = 44, SPD_STACK = 256, SPD_SHARED_BYTES = SPD_REGION * SPD_REGION * 3 * 4 + SPD_STACK * 4 + 4,
       OTHER_SHARED_BYTES = 64 * 16 * 4 + 64 * 4 };

static uint32_t max_u32(uint32_t a, uint32_t b) { return a > b ? a : b; }

void sky_limits_needed(bool single_pass_bloom, sky_limit_needs *out)
{
    /* meter.comp: 16 x 16 threads per workgroup (always built: auto exposure); bloom_spd.comp: TILE x TILE, 16 x 16.
     * The LUT passes, the sky, the tone map and the bloom chain run 64 (8 x 8, or THREADS). */
    uint32_t invocations = max_u32(16 * 16, 16 * 16);
    /* bloom spd set layout (sky/post.c): the counters and BLOOM_MAX_MIPS mips, all storage images of the compute
     * stage; it is made with every bloom chain, single pass or not. The other layouts have 1 or 2. */
    uint32_t storage_images = 1 + BLOOM_MAX_MIPS;
    uint32_t push = 0;   /* every pipeline layout's push block (shaders/glsl/shared.h, host_frame_push.h) */
    push = max_u32(push, (uint32_t)sizeof(SkyPush));
    push = max_u32(push, (uint32_t)sizeof(CompositePush));
    push = max_u32(push, (uint32_t)sizeof(SpectralSumPush));   /* 128 bytes, as HostFramePush */
    push = max_u32(push, (uint32_t)sizeof(BloomPush));
    push = max_u32(push, (uint32_t)sizeof(TonemapPush));
    push = max_u32(push, (uint32_t)sizeof(PostPush));
    push = max_u32(push, (uint32_t)sizeof(MeterPush));
    push = max_u32(push, (uint32_t)sizeof(MultiscatterPush));
    push = max_u32(push, (uint32_t)sizeof(HostFramePush));
    *out = (sky_limit_needs){.compute_work_group_invocations = invocations, .per_stage_storage_images = storage_images,
                             .compute_shared_memory = single_pass_bloom ? SPD_SHARED_BYTES : OTHER_SHARED_BYTES,
                             .push_constants = push};
}

bool sky_limits_single_pass_fits(const VkPhysicalDeviceLimits *limits)
{
    return limits->maxComputeSharedMemorySize >= SPD_SHARED_BYTES;
}

int sky_limits_check(const VkPhysicalDeviceLimits *l, bool single_pass_bloom, char *why, size_t why_size)
{
    sky_limit_needs n;
    sky_limits_needed(single_pass_bloom, &n);
    const struct { const char *name; uint32_t has, need; const char *what; } rows[] = {
        {"maxComputeWorkGroupInvocations", l->maxComputeWorkGroupInvocations, n.compute_work_group_invocations,
         "the exposure meter's 16 x 16 workgroup"},
        {"maxPerStageDescriptorStorageImages", l->maxPerStageDescriptorStorageImages, n.per_stage_storage_images,
         "the bloom's single-pass layout: its counters and 8 mips"},
        {"maxComputeSharedMemorySize", l->maxComputeSharedMemorySize, n.compute_shared_memory,
         single_pass_bloom ? "bytes, the single-pass bloom downsample's" : "bytes, the multi-scattering LUT's"},
        {"maxPushConstantsSize", l->maxPushConstantsSize, n.push_constants, "bytes, the largest push block"},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; ++i)
        if (rows[i].has < rows[i].need) {
            snprintf(why, why_size, "the device's %s is %u; vksky needs %u (%s)", rows[i].name, rows[i].has,
                     rows[i].need, rows[i].what);
            return -1;
        }
    return 0;
}

int sky_limits_apply(gpu_context *ctx, char *why, size_t why_size)
{
    const VkPhysicalDeviceLimits *l = &ctx->props.limits;
    if (ctx->memory_model_device_scope && !sky_limits_single_pass_fits(l)) {
        gpu_report(ctx, 0, "maxComputeSharedMemorySize %u: under the single-pass bloom's %u bytes; the per-level "
                   "downsample runs", l->maxComputeSharedMemorySize, (unsigned)SPD_SHARED_BYTES);
        ctx->memory_model_device_scope = false;
    }
    return sky_limits_check(l, ctx->memory_model_device_scope, why, why_size);
}

int sky_limits_report(gpu_context *ctx)
{
    char why[256];
    if (sky_limits_apply(ctx, why, sizeof why) == 0) return 0;
    gpu_report(ctx, 2, "%s", why);
    return -1;
}
