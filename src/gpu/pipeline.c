#include "gpu/pipeline.h"

VkShaderModule gpu_shader_module(const gpu_context *ctx, const uint32_t *code, size_t size, const char *name)
{
    VkShaderModuleCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = size, .pCode = code};
    VkShaderModule m;
    VK_CHECK(vkCreateShaderModule(ctx->device, &info, gpu_allocator(ctx->device), &m));
    gpu_set_name(ctx, VK_OBJECT_TYPE_SHADER_MODULE, (uint64_t)m, name);
    return m;
}

VkDescriptorSetLayout gpu_set_layout(const gpu_context *ctx, const gpu_slot *slots, uint32_t count,
                                     VkShaderStageFlags stages, const char *name)
{
    VkDescriptorSetLayoutBinding bindings[16] = {{0}};
    if (count > 16) count = 16;
    for (uint32_t i = 0; i < count; ++i)
        bindings[i] = (VkDescriptorSetLayoutBinding){
            .binding = slots[i].binding, .descriptorType = slots[i].type, .descriptorCount = 1, .stageFlags = stages};
    VkDescriptorSetLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = count, .pBindings = bindings};
    VkDescriptorSetLayout layout;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx->device, &info, gpu_allocator(ctx->device), &layout));
    gpu_set_name(ctx, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, (uint64_t)layout, name);
    return layout;
}

VkPipelineLayout gpu_pipeline_layout(const gpu_context *ctx, VkDescriptorSetLayout set_layout, uint32_t push_size,
                                     VkShaderStageFlags push_stages, const char *name)
{
    VkPushConstantRange range = {.stageFlags = push_stages, .offset = 0, .size = push_size};
    VkPipelineLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &set_layout,
        .pushConstantRangeCount = push_size ? 1 : 0,
        .pPushConstantRanges = &range,
    };
    VkPipelineLayout layout;
    VK_CHECK(vkCreatePipelineLayout(ctx->device, &info, gpu_allocator(ctx->device), &layout));
    gpu_set_name(ctx, VK_OBJECT_TYPE_PIPELINE_LAYOUT, (uint64_t)layout, name);
    return layout;
}

VkPipeline gpu_compute_pipeline(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule module, const char *name)
{
    return gpu_compute_pipeline_spec(ctx, layout, module, NULL, name);
}

VkPipeline gpu_compute_pipeline_spec(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule module,
                                     const VkSpecializationInfo *spec, const char *name)
{
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = module, .pName = "main",
                  .pSpecializationInfo = spec},
        .layout = layout,
    };
    VkPipeline p;
    VK_CHECK(vkCreateComputePipelines(ctx->device, ctx->pipeline_cache, 1, &info, gpu_allocator(ctx->device), &p));
    gpu_set_name(ctx, VK_OBJECT_TYPE_PIPELINE, (uint64_t)p, name);
    return p;
}

VkPipeline gpu_fullscreen_pipeline(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule vert,
                                   VkShaderModule frag, const VkFormat *color_formats, uint32_t color_count,
                                   gpu_blend blend, const char *name)
{
    return gpu_fullscreen_pipeline_spec(ctx, layout, vert, frag, NULL, color_formats, color_count, blend, name);
}

VkPipeline gpu_fullscreen_pipeline_spec(const gpu_context *ctx, VkPipelineLayout layout, VkShaderModule vert,
                                        VkShaderModule frag, const VkSpecializationInfo *frag_spec,
                                        const VkFormat *color_formats, uint32_t color_count, gpu_blend blend,
                                        const char *name)
{
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = frag, .pName = "main", .pSpecializationInfo = frag_spec},
    };
    VkPipelineVertexInputStateCreateInfo vertex_input = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkPipelineViewportStateCreateInfo viewport = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, .viewportCount = 1, .scissorCount = 1};
    VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL, .cullMode = VK_CULL_MODE_NONE, .lineWidth = 1.0f};
    VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    VkPipelineColorBlendAttachmentState attach[4];
    for (uint32_t i = 0; i < color_count && i < 4; ++i)
        attach[i] = (VkPipelineColorBlendAttachmentState){
            .blendEnable = blend == GPU_BLEND_ADDITIVE,
            .srcColorBlendFactor = VK_BLEND_FACTOR_ONE, .dstColorBlendFactor = VK_BLEND_FACTOR_ONE,
            .colorBlendOp = VK_BLEND_OP_ADD,
            .srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO, .dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
            .alphaBlendOp = VK_BLEND_OP_ADD,
            .colorWriteMask = 0xF};
    VkPipelineColorBlendStateCreateInfo blend_state = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = color_count, .pAttachments = attach};
    VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, .dynamicStateCount = 2, .pDynamicStates = dyn};
    VkPipelineRenderingCreateInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .colorAttachmentCount = color_count,
        .pColorAttachmentFormats = color_formats};
    VkGraphicsPipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &rendering,
        .stageCount = 2, .pStages = stages,
        .pVertexInputState = &vertex_input, .pInputAssemblyState = &assembly, .pViewportState = &viewport,
        .pRasterizationState = &raster, .pMultisampleState = &multisample, .pColorBlendState = &blend_state,
        .pDynamicState = &dynamic, .layout = layout};
    VkPipeline p;
    VK_CHECK(vkCreateGraphicsPipelines(ctx->device, ctx->pipeline_cache, 1, &info, gpu_allocator(ctx->device), &p));
    gpu_set_name(ctx, VK_OBJECT_TYPE_PIPELINE, (uint64_t)p, name);
    return p;
}

void gpu_write_uniform(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkBuffer buffer, VkDeviceSize size)
{
    VkDescriptorBufferInfo info = {.buffer = buffer, .offset = 0, .range = size};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = binding,
                              .descriptorCount = 1, .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, .pBufferInfo = &info};
    vkUpdateDescriptorSets(ctx->device, 1, &w, 0, NULL);
}

void gpu_write_sampled(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkImageView view, VkSampler sampler)
{
    VkDescriptorImageInfo info = {.sampler = sampler, .imageView = view, .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = binding,
                              .descriptorCount = 1, .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                              .pImageInfo = &info};
    vkUpdateDescriptorSets(ctx->device, 1, &w, 0, NULL);
}

void gpu_write_storage(const gpu_context *ctx, VkDescriptorSet set, uint32_t binding, VkImageView view)
{
    VkDescriptorImageInfo info = {.imageView = view, .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = binding,
                              .descriptorCount = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &info};
    vkUpdateDescriptorSets(ctx->device, 1, &w, 0, NULL);
}

VkDescriptorSet gpu_alloc_set(const gpu_context *ctx, VkDescriptorPool pool, VkDescriptorSetLayout layout, const char *name)
{
    VkDescriptorSetAllocateInfo info = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                        .descriptorPool = pool, .descriptorSetCount = 1, .pSetLayouts = &layout};
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(ctx->device, &info, &set));
    gpu_set_name(ctx, VK_OBJECT_TYPE_DESCRIPTOR_SET, (uint64_t)set, name);
    return set;
}

VkSampler gpu_linear_clamp_sampler(const gpu_context *ctx, const char *name)
{
    VkSamplerCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_LINEAR, .minFilter = VK_FILTER_LINEAR,
        .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .maxLod = 0.0f};
    VkSampler s;
    VK_CHECK(vkCreateSampler(ctx->device, &info, gpu_allocator(ctx->device), &s));
    gpu_set_name(ctx, VK_OBJECT_TYPE_SAMPLER, (uint64_t)s, name);
    return s;
}

void gpu_begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, const gpu_attachment *attachments, uint32_t count)
{
    VkRenderingAttachmentInfo infos[4];
    for (uint32_t i = 0; i < count && i < 4; ++i)
        infos[i] = (VkRenderingAttachmentInfo){
            .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
            .imageView = attachments[i].view,
            .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            .loadOp = attachments[i].load,
            .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
    VkRenderingInfo info = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, extent},
        .layerCount = 1,
        .colorAttachmentCount = count,
        .pColorAttachments = infos};
    vkCmdBeginRendering(cmd, &info);
    VkViewport vp = {0, 0, (float)extent.width, (float)extent.height, 0, 1};
    VkRect2D scissor = {{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}
