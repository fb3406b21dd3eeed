/* Auto exposure's GPU meter (sky/meter.h; shaders/glsl/meter.comp). */
#include "sky/meter.h"
#include "sky/shaders.h"
#include "meter_comp.h"
#include <string.h>

#define METER_FLOOR_CD_M2 1e-4   /* docs/units.md: a black pixel does not drag the mean to zero  */

void meter_write_descriptor(const gpu_context *ctx, VkDescriptorSet set, const meter_pass *m)
{
    VkDescriptorBufferInfo info = {.buffer = m->buffer.buffer, .offset = 0, .range = m->buffer.size};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set,
                              .dstBinding = VKSKY_BINDING_METER, .descriptorCount = 1,
                              .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &info};
    vkUpdateDescriptorSets(ctx->device, 1, &w, 0, NULL);
}

void meter_create(meter_pass *m, const pass_shared *s, VkDescriptorPool pool, const gpu_image *hdr)
{
    const gpu_context *ctx = s->ctx;
    *m = (meter_pass){.tiles = {(hdr->extent.width + VKSKY_METER_TILE - 1) / VKSKY_METER_TILE,
                                (hdr->extent.height + VKSKY_METER_TILE - 1) / VKSKY_METER_TILE}};
    VkDeviceSize partials = (VkDeviceSize)m->tiles.width * m->tiles.height;
    /* Host-visible (the host reads a slot's result); a few kilobytes, so the GPU's reads over the bus cost nothing. */
    gpu_buffer_create(ctx, &m->buffer, "exposure meter", VKSKY_METER_SLOTS * 16 + 16 + partials * 8,
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    memset(m->buffer.mapped, 0, (size_t)m->buffer.size);   /* a slot never written reads as no exposure, not garbage */
    const gpu_slot slots[] = {{VKSKY_BINDING_POST_SOURCE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                              {VKSKY_BINDING_METER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
    m->set_layout = gpu_set_layout(ctx, slots, 2, VK_SHADER_STAGE_COMPUTE_BIT, "meter set layout");
    m->layout = gpu_pipeline_layout(ctx, m->set_layout, sizeof(MeterPush), VK_SHADER_STAGE_COMPUTE_BIT, "meter layout");
    m->ctx = ctx;
    m->set = gpu_alloc_set(ctx, pool, m->set_layout, "meter set");
    gpu_write_sampled(ctx, m->set, VKSKY_BINDING_POST_SOURCE, hdr->view, s->linear_clamp);
    meter_write_descriptor(ctx, m->set, m);
}

void meter_destroy(meter_pass *m, const pass_shared *s)
{
    VkDevice d = s->ctx->device;
    if (m->pipeline) vkDestroyPipeline(d, m->pipeline, gpu_allocator(d));
    if (m->layout) vkDestroyPipelineLayout(d, m->layout, gpu_allocator(d));
    if (m->set_layout) vkDestroyDescriptorSetLayout(d, m->set_layout, gpu_allocator(d));
    gpu_buffer_destroy(s->ctx, &m->buffer);
    *m = (meter_pass){0};
}

static void dispatch(meter_pass *m, VkCommandBuffer cmd, const MeterPush *push, uint32_t x, uint32_t y)
{
    if (!m->pipeline) {
        VkShaderModule mod = gpu_shader_module(m->ctx, spv_meter_comp, sizeof spv_meter_comp, "meter.comp");
        m->pipeline = gpu_compute_pipeline(m->ctx, m->layout, mod, "meter");
        vkDestroyShaderModule(m->ctx->device, mod, gpu_allocator(m->ctx->device));
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m->layout, 0, 1, &m->set, 0, NULL);
    vkCmdPushConstants(cmd, m->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
    vkCmdDispatch(cmd, x, y, 1);
}

void meter_record_tiles(meter_pass *m, VkCommandBuffer cmd, double scale, bool all_pixels, uint32_t first_row,
                        uint32_t rows, bool fisheye, int whole_row0)
{
    /* Rows first_row .. first_row + rows - 1 count (0 rows: all of them); row indices are exact in a float. */
    uint32_t end = rows ? first_row + rows : m->tiles.height * VKSKY_METER_TILE;
    MeterPush push = {.params = {(float)scale, (float)METER_FLOOR_CD_M2, all_pixels ? 1.0f : 0.0f, fisheye ? 1.0f : 0.0f},
                      .pass = {0.0f, rows ? (float)first_row : 0.0f, fisheye ? (float)whole_row0 : 0.0f, (float)end}};
    dispatch(m, cmd, &push, m->tiles.width, m->tiles.height);
}

void meter_record_average(meter_pass *m, VkCommandBuffer cmd, double scale, bool all_pixels, uint32_t slot,
                          double ease)
{
    MeterPush push = {.params = {(float)scale, (float)METER_FLOOR_CD_M2, all_pixels ? 1.0f : 0.0f, (float)slot},
                      .pass = {1.0f, (float)(m->tiles.width * m->tiles.height), ease > 0.0 ? (float)ease : 1.0f, 0.0f}};
    dispatch(m, cmd, &push, 1, 1);
}

meter_result meter_read(const gpu_context *ctx, const meter_pass *m, uint32_t slot)
{
    gpu_buffer_invalidate(ctx, &m->buffer);
    meter_result out;
    memcpy(&out, (const char *)m->buffer.mapped + 16 * (slot % VKSKY_METER_SLOTS), sizeof out);
    return out;
}
