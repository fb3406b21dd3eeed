/* The aerial-perspective volume's resources and build dispatch (ap_volume.h). */
#include "sky/ap_volume.h"
#include "ap_volume_comp.h"
#include <stdio.h>
#include <string.h>

ap_volume_desc ap_volume_desc_default(void)
{
    return (ap_volume_desc){.width = 32, .height = 32, .depth = 32, .range_km = 32.0f, .distribution = 2.0f};
}

void ap_volume_spec_make(const VkSpecializationInfo *base, const ap_volume_desc *d, ap_volume_spec *out)
{
    memset(out, 0, sizeof *out);
    uint32_t n = base ? base->mapEntryCount : 0;
    size_t size = base ? base->dataSize : 0;
    size_t at = (size + 3) & ~(size_t)3;   /* the two floats, 4-aligned after the variant's data */
    if (n > VKSKY_SPEC_COUNT || at + 2 * sizeof(float) > sizeof out->data) {
        gpu_report(NULL, 2, "internal error: specialization data too large for the volume (%zu bytes)", size);
        n = 0, size = 0, at = 0;
    }
    if (n) memcpy(out->entries, base->pMapEntries, n * sizeof *out->entries);
    if (size) memcpy(out->data, base->pData, size);
    memcpy(out->data + at, &d->range_km, sizeof(float));
    memcpy(out->data + at + sizeof(float), &d->distribution, sizeof(float));
    out->entries[n] = (VkSpecializationMapEntry){VKSKY_SPEC_AP_RANGE, (uint32_t)at, sizeof(float)};
    out->entries[n + 1] = (VkSpecializationMapEntry){VKSKY_SPEC_AP_DISTRIBUTION, (uint32_t)(at + sizeof(float)),
                                                     sizeof(float)};
    out->info = (VkSpecializationInfo){.mapEntryCount = n + 2, .pMapEntries = out->entries,
                                       .dataSize = at + 2 * sizeof(float), .pData = out->data};
}

int ap_volume_create(ap_volume *a, sky_renderer *r, const ap_volume_desc *d, char *err, size_t err_size)
{
    const gpu_context *ctx = r->ctx;
    memset(a, 0, sizeof *a);
    uint32_t limit = ctx->props.limits.maxImageDimension3D;
    if (d->width < 1 || d->height < 1 || d->depth < 1 || d->width > 512 || d->height > 512 || d->depth > 512 ||
        d->width > limit || d->height > limit || 3 * d->depth > limit) {
        snprintf(err, err_size, "a %ux%ux%u froxel volume does not fit (1 to 512 each; the device holds 3D images of "
                 "%u texels a side, the volume needs 3 x depth)", d->width, d->height, d->depth, limit);
        return -1;
    }
    if (!(d->range_km > 0.0f) || !(d->distribution >= 1.0f && d->distribution <= 4.0f)) {
        snprintf(err, err_size, "volume range %g km / distribution %g: need a range > 0 and a distribution in [1, 4]",
                 d->range_km, d->distribution);
        return -1;
    }
    a->desc = *d;
    gpu_image_create_3d(ctx, &a->image, "ap_volume", VK_FORMAT_R16G16B16A16_SFLOAT, d->width, d->height,
                        3 * d->depth, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    VkDescriptorPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                        .poolSizeCount = 3, .pPoolSizes = sizes};
    VK_CHECK(vkCreateDescriptorPool(ctx->device, &pinfo, gpu_allocator(ctx->device), &a->pool));
    const gpu_slot slots[] = {{VKSKY_BINDING_ATMOSPHERE, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                              {VKSKY_BINDING_TRANSMITTANCE_LUT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                              {VKSKY_BINDING_MULTISCATTER_LUT, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                              {VKSKY_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
    a->set_layout = gpu_set_layout(ctx, slots, 4, VK_SHADER_STAGE_COMPUTE_BIT, "ap_volume");
    a->layout = gpu_pipeline_layout(ctx, a->set_layout, sizeof(CompositePush), VK_SHADER_STAGE_COMPUTE_BIT,
                                    "ap_volume");
    a->set = gpu_alloc_set(ctx, a->pool, a->set_layout, "ap_volume");
    const pass_shared *s = &r->shared;
    gpu_write_uniform(ctx, a->set, VKSKY_BINDING_ATMOSPHERE, s->atmosphere_ubo.buffer, sizeof(AtmosphereParams));
    gpu_write_sampled(ctx, a->set, VKSKY_BINDING_TRANSMITTANCE_LUT, r->luts.transmittance.view, s->linear_clamp);
    gpu_write_sampled(ctx, a->set, VKSKY_BINDING_MULTISCATTER_LUT, r->luts.multiscatter_view, s->linear_clamp);
    gpu_write_storage(ctx, a->set, VKSKY_BINDING_OUTPUT, a->image.view);
    ap_volume_spec spec;
    ap_volume_spec_make(s->spec, d, &spec);
    VkShaderModule m = gpu_shader_module(ctx, spv_ap_volume_comp, sizeof spv_ap_volume_comp, "ap_volume.comp");
    a->pipeline = gpu_compute_pipeline_spec(ctx, a->layout, m, &spec.info, "ap_volume");
    vkDestroyShaderModule(ctx->device, m, gpu_allocator(ctx->device));
    return 0;
}

void ap_volume_destroy(ap_volume *a, const sky_renderer *r)
{
    const gpu_context *ctx = r->ctx;
    if (!a->pipeline) return;
    vkDeviceWaitIdle(ctx->device);
    vkDestroyPipeline(ctx->device, a->pipeline, gpu_allocator(ctx->device));
    vkDestroyPipelineLayout(ctx->device, a->layout, gpu_allocator(ctx->device));
    vkDestroyDescriptorSetLayout(ctx->device, a->set_layout, gpu_allocator(ctx->device));
    vkDestroyDescriptorPool(ctx->device, a->pool, gpu_allocator(ctx->device));
    gpu_image_destroy(ctx, &a->image);
    memset(a, 0, sizeof *a);
}

void ap_volume_dispatch(const ap_volume *a, VkCommandBuffer cmd, const CompositePush *push)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, a->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, a->layout, 0, 1, &a->set, 0, NULL);
    vkCmdPushConstants(cmd, a->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
    vkCmdDispatch(cmd, (a->desc.width + 3) / 4, (a->desc.height + 3) / 4, (a->desc.depth + 3) / 4);
}
