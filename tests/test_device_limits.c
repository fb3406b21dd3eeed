/* The device limits vksky checks at creation (src/sky/limits.c, issue 25):
 * 1. the needs against the SPIR-V the build compiled, read here independently of the C figures: each compute
 *    module's workgroup size (LocalSize / LocalSizeId), its Workgroup variables' bytes (the types walked: vec3 = 12
 *    bytes, bool = 4), its storage images (UniformConstant image variables with Sampled = 2, arrays counted);
 * 2. the check fed Vulkan 1.3's required minimums refuses, naming the limit, the minimum and the need, one limit at a
 *    time as each is raised to the need;
 * 3. this machine's device (lavapipe in CI) passes, its real limits read from Vulkan. */
#include "sky/limits.h"
#include "gpu/context.h"
#include <stdio.h>
#include "check.h"
#include <string.h>

#include "ap_volume_comp.h"
#include "bloom_down_comp.h"
#include "bloom_spd_comp.h"
#include "bloom_up_comp.h"
#include "composite_comp.h"
#include "composite_volume_comp.h"
#include "ground_irradiance_lut_comp.h"
#include "ground_irradiance_lut_s4_comp.h"
#include "host_frame_comp.h"
#include "host_frame_f32_comp.h"
#include "meter_comp.h"
#include "multiscatter_lut_comp.h"
#include "multiscatter_lut_f32_comp.h"
#include "multiscatter_lut_f32_s4_comp.h"
#include "multiscatter_lut_s4_comp.h"
#include "sky_blend_comp.h"
#include "sky_blend_s4_comp.h"
#include "sky_fill_comp.h"
#include "sky_lookup_comp.h"
#include "sky_lookup_s4_comp.h"
#include "sky_march_comp.h"
#include "sky_march_s4_comp.h"
#include "skyview_lut_comp.h"
#include "skyview_lut_s4_comp.h"
#include "tonemap_comp.h"
#include "tonemap_composite_comp.h"
#include "tonemap_composite_s4_comp.h"
#include "transmittance_lut_comp.h"
#include "transmittance_lut_f32_comp.h"
#include "transmittance_lut_f32_s4_comp.h"
#include "transmittance_lut_s4_comp.h"


#define MODULE(name) {#name, name, sizeof name / 4}
static const struct { const char *name; const uint32_t *words; size_t count; } modules[] = {
    MODULE(spv_ap_volume_comp), MODULE(spv_bloom_down_comp), MODULE(spv_bloom_spd_comp), MODULE(spv_bloom_up_comp),
    MODULE(spv_composite_comp), MODULE(spv_composite_volume_comp), MODULE(spv_ground_irradiance_lut_comp),
    MODULE(spv_ground_irradiance_lut_s4_comp), MODULE(spv_host_frame_comp), MODULE(spv_host_frame_f32_comp),
    MODULE(spv_meter_comp), MODULE(spv_multiscatter_lut_comp), MODULE(spv_multiscatter_lut_f32_comp),
    MODULE(spv_multiscatter_lut_f32_s4_comp), MODULE(spv_multiscatter_lut_s4_comp), MODULE(spv_sky_blend_comp),
    MODULE(spv_sky_blend_s4_comp), MODULE(spv_sky_fill_comp), MODULE(spv_sky_lookup_comp),
    MODULE(spv_sky_lookup_s4_comp), MODULE(spv_sky_march_comp), MODULE(spv_sky_march_s4_comp),
    MODULE(spv_skyview_lut_comp), MODULE(spv_skyview_lut_s4_comp), MODULE(spv_tonemap_comp),
    MODULE(spv_tonemap_composite_comp), MODULE(spv_tonemap_composite_s4_comp), MODULE(spv_transmittance_lut_comp),
    MODULE(spv_transmittance_lut_f32_comp), MODULE(spv_transmittance_lut_f32_s4_comp),
    MODULE(spv_transmittance_lut_s4_comp),
};

/* SPIR-V opcodes and enums (the SPIR-V specification, sections 3.x). */
enum { OP_EXECUTION_MODE = 16, OP_TYPE_BOOL = 20, OP_TYPE_INT = 21, OP_TYPE_FLOAT = 22, OP_TYPE_VECTOR = 23,
       OP_TYPE_MATRIX = 24, OP_TYPE_IMAGE = 25, OP_TYPE_ARRAY = 28, OP_TYPE_STRUCT = 30, OP_TYPE_POINTER = 32,
       OP_CONSTANT = 43, OP_VARIABLE = 59, OP_EXECUTION_MODE_ID = 331, MODE_LOCAL_SIZE = 17, MODE_LOCAL_SIZE_ID = 38,
       STORAGE_UNIFORM_CONSTANT = 0, STORAGE_WORKGROUP = 4, MAX_IDS = 1 << 16 };

typedef struct spirv_info { uint32_t invocations, shared_bytes, storage_images; } spirv_info;

/* Per id: the instruction's word offset (types, constants). */
static uint32_t at[MAX_IDS];

static uint32_t type_bytes(const uint32_t *w, uint32_t id)
{
    const uint32_t *i = w + at[id];
    switch (i[0] & 0xffff) {
    case OP_TYPE_BOOL: return 4;
    case OP_TYPE_INT: case OP_TYPE_FLOAT: return i[2] / 8;
    case OP_TYPE_VECTOR: case OP_TYPE_MATRIX: return i[3] * type_bytes(w, i[2]);
    case OP_TYPE_ARRAY: return w[at[i[3]] + 3] * type_bytes(w, i[2]);   /* the length: an OpConstant */
    case OP_TYPE_STRUCT: {
        uint32_t n = 0;
        for (uint32_t k = 2; k < (i[0] >> 16); ++k) n += type_bytes(w, i[k]);
        return n;
    }
    default: return 0;
    }
}

/* Storage images a variable of this type binds (an image with Sampled = 2, or an array of them). */
static uint32_t storage_images(const uint32_t *w, uint32_t id)
{
    const uint32_t *i = w + at[id];
    if ((i[0] & 0xffff) == OP_TYPE_IMAGE) return i[7] == 2 ? 1 : 0;
    if ((i[0] & 0xffff) == OP_TYPE_ARRAY) return w[at[i[3]] + 3] * storage_images(w, i[2]);
    return 0;
}

static spirv_info spirv_read(const uint32_t *w, size_t count)
{
    spirv_info info = {0};
    memset(at, 0, sizeof at);
    uint32_t size[3] = {1, 1, 1}, size_ids[3] = {0, 0, 0};
    for (size_t p = 5; p < count;) {
        uint32_t n = w[p] >> 16, op = w[p] & 0xffff;
        if (n == 0) break;
        if (op >= OP_TYPE_BOOL && op <= OP_TYPE_POINTER) at[w[p + 1] % MAX_IDS] = (uint32_t)p;
        if (op == OP_CONSTANT) at[w[p + 2] % MAX_IDS] = (uint32_t)p;
        if (op == OP_EXECUTION_MODE && w[p + 2] == MODE_LOCAL_SIZE) memcpy(size, w + p + 3, sizeof size);
        if (op == OP_EXECUTION_MODE_ID && w[p + 2] == MODE_LOCAL_SIZE_ID) memcpy(size_ids, w + p + 3, sizeof size_ids);
        if (op == OP_VARIABLE) {
            const uint32_t *ptr = w + at[w[p + 1] % MAX_IDS];   /* OpTypePointer: storage class, pointee */
            if (w[p + 3] == STORAGE_WORKGROUP) info.shared_bytes += type_bytes(w, ptr[3]);
            if (w[p + 3] == STORAGE_UNIFORM_CONSTANT) info.storage_images += storage_images(w, ptr[3]);
        }
        p += n;
    }
    for (int k = 0; k < 3; ++k)
        if (size_ids[k]) size[k] = w[at[size_ids[k]] + 3];
    info.invocations = size[0] * size[1] * size[2];
    return info;
}

/* Vulkan 1.3 specification, "Limits", table "Required Limits": the minimums every Vulkan 1.3 device has (the
 * Vulkan 1.3 column; maxComputeWorkGroupInvocations 128, maxPerStageDescriptorStorageImages 4,
 * maxComputeSharedMemorySize 16384, maxPushConstantsSize 128). */
static VkPhysicalDeviceLimits spec_minimums(void)
{
    return (VkPhysicalDeviceLimits){.maxImageDimension2D = 4096, .maxComputeWorkGroupInvocations = 128,
                                    .maxComputeWorkGroupSize = {128, 128, 64},
                                    .maxPerStageDescriptorStorageImages = 4, .maxComputeSharedMemorySize = 16384,
                                    .maxPushConstantsSize = 128, .maxPerStageDescriptorSampledImages = 16};
}

static void expect_refusal(const VkPhysicalDeviceLimits *l, bool single_pass, const char *limit, uint32_t has,
                           uint32_t need)
{
    char why[256] = "", want_has[64], want_need[64];
    int rc = sky_limits_check(l, single_pass, why, sizeof why);
    snprintf(want_has, sizeof want_has, "%s is %u;", limit, has);
    snprintf(want_need, sizeof want_need, "vksky needs %u ", need);
    CHECK(rc == -1 && strstr(why, want_has) && strstr(why, want_need) && !strchr(why, '\n'),
          "refusal of %s (%u < %u): rc %d, \"%s\"", limit, has, need, rc, why);
}

int main(void)
{
    /* 1. The needs against the SPIR-V. */
    spirv_info most = {0};
    uint32_t spd_shared = 0, other_shared = 0;
    for (size_t m = 0; m < sizeof modules / sizeof modules[0]; ++m) {
        spirv_info i = spirv_read(modules[m].words, modules[m].count);
        printf("%-36s %4u invocations %6u shared bytes %2u storage images\n", modules[m].name, i.invocations,
               i.shared_bytes, i.storage_images);
        if (i.invocations > most.invocations) most.invocations = i.invocations;
        if (i.storage_images > most.storage_images) most.storage_images = i.storage_images;
        if (!strcmp(modules[m].name, "spv_bloom_spd_comp")) spd_shared = i.shared_bytes;
        else if (i.shared_bytes > other_shared) other_shared = i.shared_bytes;
    }
    sky_limit_needs with_spd, without;
    sky_limits_needed(true, &with_spd);
    sky_limits_needed(false, &without);
    CHECK(most.invocations == with_spd.compute_work_group_invocations, "invocations: SPIR-V %u, need %u",
          most.invocations, with_spd.compute_work_group_invocations);
    CHECK(most.storage_images == with_spd.per_stage_storage_images, "storage images: SPIR-V %u, need %u",
          most.storage_images, with_spd.per_stage_storage_images);
    CHECK(spd_shared == with_spd.compute_shared_memory, "single pass shared bytes: SPIR-V %u, need %u", spd_shared,
          with_spd.compute_shared_memory);
    CHECK(other_shared > 0 && other_shared <= without.compute_shared_memory,
          "other passes' shared bytes: SPIR-V %u, need %u", other_shared, without.compute_shared_memory);
    CHECK(with_spd.push_constants > 0 && with_spd.push_constants <= 128, "push constants %u", with_spd.push_constants);

    /* 2. The spec's minimums refused, a limit at a time. */
    VkPhysicalDeviceLimits l = spec_minimums();
    expect_refusal(&l, false, "maxComputeWorkGroupInvocations", 128, with_spd.compute_work_group_invocations);
    l.maxComputeWorkGroupInvocations = with_spd.compute_work_group_invocations;
    expect_refusal(&l, false, "maxPerStageDescriptorStorageImages", 4, with_spd.per_stage_storage_images);
    l.maxPerStageDescriptorStorageImages = with_spd.per_stage_storage_images;
    char why[256] = "";
    CHECK(sky_limits_check(&l, false, why, sizeof why) == 0, "the needs met without the single pass: \"%s\"", why);
    expect_refusal(&l, true, "maxComputeSharedMemorySize", 16384, with_spd.compute_shared_memory);
    CHECK(!sky_limits_single_pass_fits(&l), "16384 bytes hold the single pass");
    l.maxComputeSharedMemorySize = with_spd.compute_shared_memory;
    CHECK(sky_limits_single_pass_fits(&l) && sky_limits_check(&l, true, why, sizeof why) == 0,
          "the needs met with the single pass: \"%s\"", why);
    l.maxComputeSharedMemorySize -= 1;
    expect_refusal(&l, true, "maxComputeSharedMemorySize", with_spd.compute_shared_memory - 1,
                   with_spd.compute_shared_memory);

    /* 3. This machine's device. */
    gpu_context ctx;
    gpu_context_desc desc = {.device_index = -1};
    if (gpu_context_create(&ctx, &desc) != 0) {
        fprintf(stderr, "FAIL: no Vulkan device\n");
        return 1;
    }
    const VkPhysicalDeviceLimits *real = &ctx.props.limits;
    printf("%s: maxComputeWorkGroupInvocations %u, maxPerStageDescriptorStorageImages %u, "
           "maxComputeSharedMemorySize %u, maxPushConstantsSize %u\n", ctx.props.deviceName,
           real->maxComputeWorkGroupInvocations, real->maxPerStageDescriptorStorageImages,
           real->maxComputeSharedMemorySize, real->maxPushConstantsSize);
    CHECK(sky_limits_apply(&ctx, why, sizeof why) == 0, "%s refused: \"%s\"", ctx.props.deviceName, why);
    gpu_context_destroy(&ctx);
    if (check_failures) return 1;
    printf("device limits: ok\n");
    return 0;
}
