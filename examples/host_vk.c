/* The example host's Vulkan boilerplate (host_vk.h). */
#include "host_vk.h"
#include "sky_host_scene.h"
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned validation_messages;

void hv_fail(const char *file, int line, const char *call, VkResult r)
{
    fprintf(stderr, "sky_host: %s:%d: %s failed (VkResult %d)\n", file, line, call, (int)r);
    exit(1);
}

unsigned hv_validation_messages(void) { return validation_messages; }

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)type, (void)user;
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        ++validation_messages;
        fprintf(stderr, "sky_host: validation %s: [ %s ] %s\n",
                severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
                data->pMessageIdName ? data->pMessageIdName : "?", data->pMessage);
    }
    return VK_FALSE;
}

void hv_device_create(hv_device *d, bool validate, const char *const *instance_exts, uint32_t ext_count,
                      bool swapchain, const VkPhysicalDeviceVulkan13Features *features13)
{
    memset(d, 0, sizeof *d);
    const char *exts[16];
    uint32_t n = 0;
    for (uint32_t i = 0; i < ext_count && n < 15; ++i) exts[n++] = instance_exts[i];
    if (validate) exts[n++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const char *layer = "VK_LAYER_KHRONOS_validation";
    VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT vf = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                  .enabledValidationFeatureCount = 1, .pEnabledValidationFeatures = &sync};
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "vksky sky_host",
                             .apiVersion = VK_API_VERSION_1_3};
    VkInstanceCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pNext = validate ? &vf : NULL,
                               .pApplicationInfo = &app, .enabledLayerCount = validate ? 1 : 0,
                               .ppEnabledLayerNames = &layer, .enabledExtensionCount = n,
                               .ppEnabledExtensionNames = exts};
    HV_CHECK(vkCreateInstance(&ii, NULL, &d->instance));
    if (validate) {
        VkDebugUtilsMessengerCreateInfoEXT mi = {
            .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
            .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
            .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
            .pfnUserCallback = on_message};
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(d->instance, "vkCreateDebugUtilsMessengerEXT");
        if (create) HV_CHECK(create(d->instance, &mi, NULL, &d->messenger));
    }
    /* The first device with a queue family that does graphics and compute. */
    VkPhysicalDevice gpus[8];
    uint32_t count = 8;
    vkEnumeratePhysicalDevices(d->instance, &count, gpus);
    for (uint32_t g = 0; g < count && !d->gpu; ++g) {
        VkQueueFamilyProperties fam[16];
        uint32_t fc = 16;
        vkGetPhysicalDeviceQueueFamilyProperties(gpus[g], &fc, fam);
        for (uint32_t f = 0; f < fc; ++f)
            if ((fam[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                d->gpu = gpus[g], d->family = f;
                break;
            }
    }
    if (!d->gpu) {
        fprintf(stderr, "sky_host: no Vulkan device with a graphics + compute queue\n");
        exit(1);
    }
    VkPhysicalDeviceVulkan13Features f13 = *features13;
    f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, f13.pNext = NULL;
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueFamilyIndex = d->family,
                                  .queueCount = 1, .pQueuePriorities = &priority};
    const char *dev_ext = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    VkDeviceCreateInfo di = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &f13, .queueCreateInfoCount = 1,
                             .pQueueCreateInfos = &qi, .enabledExtensionCount = swapchain ? 1 : 0,
                             .ppEnabledExtensionNames = &dev_ext};
    HV_CHECK(vkCreateDevice(d->gpu, &di, NULL, &d->device));
    vkGetDeviceQueue(d->device, d->family, 0, &d->queue);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = d->family};
    HV_CHECK(vkCreateCommandPool(d->device, &pi, NULL, &d->pool));
}

void hv_device_destroy(hv_device *d)
{
    vkDestroyCommandPool(d->device, d->pool, NULL);
    vkDestroyDevice(d->device, NULL);
    if (d->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(d->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy) destroy(d->instance, d->messenger, NULL);
    }
    vkDestroyInstance(d->instance, NULL);
}

static uint32_t memory_type(const hv_device *d, uint32_t bits, VkMemoryPropertyFlags want)
{
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(d->gpu, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
    fprintf(stderr, "sky_host: no memory type with properties 0x%x\n", want);
    exit(1);
}

void hv_image_create(const hv_device *d, hv_image *img, VkFormat format, VkExtent2D extent, VkImageUsageFlags usage,
                     VkImageAspectFlags aspect)
{
    VkImageCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {extent.width, extent.height, 1}, .mipLevels = 1,
                            .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = usage};
    HV_CHECK(vkCreateImage(d->device, &ci, NULL, &img->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d->device, img->image, &req);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = memory_type(d, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)};
    HV_CHECK(vkAllocateMemory(d->device, &ai, NULL, &img->memory));
    HV_CHECK(vkBindImageMemory(d->device, img->image, img->memory, 0));
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = img->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {aspect, 0, 1, 0, 1}};
    HV_CHECK(vkCreateImageView(d->device, &vi, NULL, &img->view));
    img->format = format, img->extent = extent;
}

void hv_image_destroy(const hv_device *d, hv_image *img)
{
    vkDestroyImageView(d->device, img->view, NULL);
    vkDestroyImage(d->device, img->image, NULL);
    vkFreeMemory(d->device, img->memory, NULL);
}

void hv_buffer_create(const hv_device *d, hv_buffer *b, VkDeviceSize size, VkBufferUsageFlags usage)
{
    VkBufferCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    HV_CHECK(vkCreateBuffer(d->device, &ci, NULL, &b->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(d->device, b->buffer, &req);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = memory_type(d, req.memoryTypeBits,
                                                              VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                  VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
    HV_CHECK(vkAllocateMemory(d->device, &ai, NULL, &b->memory));
    HV_CHECK(vkBindBufferMemory(d->device, b->buffer, b->memory, 0));
    HV_CHECK(vkMapMemory(d->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
}

void hv_buffer_destroy(const hv_device *d, hv_buffer *b)
{
    vkDestroyBuffer(d->device, b->buffer, NULL);
    vkFreeMemory(d->device, b->memory, NULL);
}

VkPipeline hv_pipeline(const hv_device *d, VkPipelineLayout layout, const uint32_t *vs, size_t vs_size,
                       const uint32_t *fs, size_t fs_size, VkFormat color, VkFormat depth, bool mesh)
{
    VkShaderModule m[2];
    const uint32_t *code[2] = {vs, fs};
    size_t size[2] = {vs_size, fs_size};
    for (int i = 0; i < 2; ++i) {
        VkShaderModuleCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = size[i],
                                       .pCode = code[i]};
        HV_CHECK(vkCreateShaderModule(d->device, &si, NULL, &m[i]));
    }
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = m[0], .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = m[1], .pName = "main"}};
    VkVertexInputBindingDescription binding = {0, 7 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attrs[3] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                                  {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12},
                                                  {2, 0, VK_FORMAT_R32_SFLOAT, 24}};
    VkPipelineVertexInputStateCreateInfo vin = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
                                                .vertexBindingDescriptionCount = mesh ? 1 : 0,
                                                .pVertexBindingDescriptions = &binding,
                                                .vertexAttributeDescriptionCount = mesh ? 3 : 0,
                                                .pVertexAttributeDescriptions = attrs};
    VkPipelineInputAssemblyStateCreateInfo ia = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
                                                 .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkPipelineViewportStateCreateInfo vp = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
                                            .viewportCount = 1, .scissorCount = 1};
    VkPipelineRasterizationStateCreateInfo rs = {.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
                                                 .polygonMode = VK_POLYGON_MODE_FILL, .cullMode = VK_CULL_MODE_NONE,
                                                 .lineWidth = 1.0f};
    VkPipelineMultisampleStateCreateInfo ms = {.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
                                               .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    VkPipelineDepthStencilStateCreateInfo ds = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
                                                .depthTestEnable = mesh, .depthWriteEnable = mesh,
                                                .depthCompareOp = VK_COMPARE_OP_GREATER};
    VkPipelineColorBlendAttachmentState blend = {.colorWriteMask = 0xf};
    VkPipelineColorBlendStateCreateInfo cb = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                              .attachmentCount = 1, .pAttachments = &blend};
    VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                           .dynamicStateCount = 2, .pDynamicStates = dyn};
    VkPipelineRenderingCreateInfo ri = {.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
                                        .colorAttachmentCount = 1, .pColorAttachmentFormats = &color,
                                        .depthAttachmentFormat = mesh ? depth : VK_FORMAT_UNDEFINED};
    VkGraphicsPipelineCreateInfo gi = {.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, .pNext = &ri,
                                       .stageCount = 2, .pStages = stages, .pVertexInputState = &vin,
                                       .pInputAssemblyState = &ia, .pViewportState = &vp, .pRasterizationState = &rs,
                                       .pMultisampleState = &ms, .pDepthStencilState = &ds, .pColorBlendState = &cb,
                                       .pDynamicState = &dy, .layout = layout};
    VkPipeline p;
    HV_CHECK(vkCreateGraphicsPipelines(d->device, VK_NULL_HANDLE, 1, &gi, NULL, &p));
    vkDestroyShaderModule(d->device, m[0], NULL);
    vkDestroyShaderModule(d->device, m[1], NULL);
    return p;
}

void hv_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 src_stage,
                VkAccessFlags2 src_access, VkImageLayout from, VkPipelineStageFlags2 dst_stage,
                VkAccessFlags2 dst_access, VkImageLayout to)
{
    VkImageMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .srcStageMask = src_stage,
                               .srcAccessMask = src_access, .dstStageMask = dst_stage, .dstAccessMask = dst_access,
                               .oldLayout = from, .newLayout = to, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                               .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                               .subresourceRange = {aspect, 0, 1, 0, 1}};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                            .pImageMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}

VkCommandBuffer hv_begin(const hv_device *d)
{
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = d->pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer cmd;
    HV_CHECK(vkAllocateCommandBuffers(d->device, &ai, &cmd));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    HV_CHECK(vkBeginCommandBuffer(cmd, &bi));
    return cmd;
}

void hv_submit_wait(const hv_device *d, VkCommandBuffer cmd)
{
    HV_CHECK(vkEndCommandBuffer(cmd));
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1,
                        .pCommandBufferInfos = &ci};
    HV_CHECK(vkQueueSubmit2(d->queue, 1, &si, VK_NULL_HANDLE));
    HV_CHECK(vkQueueWaitIdle(d->queue));
    vkFreeCommandBuffers(d->device, d->pool, 1, &cmd);
}

float hv_half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h >> 15) << 31, e = (h >> 10) & 31, m = h & 1023, bits;
    if (e == 0) {   /* zero or subnormal: m x 2^-24 */
        float f = (float)m / 16777216.0f;
        return sign ? -f : f;
    }
    bits = sign | (e == 31 ? 0xff << 23 : (e + 112) << 23) | m << 13;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static void put(FILE *f, const void *p, size_t n) { fwrite(p, 1, n, f); }
static void put_i32(FILE *f, int32_t v) { put(f, &v, 4); }
static void attr(FILE *f, const char *name, const char *type, int32_t size)
{
    put(f, name, strlen(name) + 1), put(f, type, strlen(type) + 1), put_i32(f, size);
}

int hv_write_exr(const char *path, const float *rgba, int width, int height)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    put_i32(f, 20000630), put_i32(f, 2);   /* magic, version 2 (single-part scanline) */
    /* Channels in the file's order (alphabetical): A, B, G, R, each FLOAT (2), sampling 1 x 1. */
    const char *names = "ABGR";
    attr(f, "channels", "chlist", 4 * 18 + 1);
    for (int c = 0; c < 4; ++c) {
        char ch[2] = {names[c], 0};
        int32_t rec[4] = {2, 0, 1, 1};   /* pixel type, pLinear + reserved, x sampling, y sampling */
        put(f, ch, 2), put(f, rec, sizeof rec);
    }
    put(f, "", 1);
    attr(f, "compression", "compression", 1), put(f, "", 1);   /* NO_COMPRESSION */
    int32_t box[4] = {0, 0, width - 1, height - 1};
    attr(f, "dataWindow", "box2i", 16), put(f, box, 16);
    attr(f, "displayWindow", "box2i", 16), put(f, box, 16);
    attr(f, "lineOrder", "lineOrder", 1), put(f, "", 1);       /* INCREASING_Y */
    float one = 1.0f, centre[2] = {0, 0};
    attr(f, "pixelAspectRatio", "float", 4), put(f, &one, 4);
    attr(f, "screenWindowCenter", "v2f", 8), put(f, centre, 8);
    attr(f, "screenWindowWidth", "float", 4), put(f, &one, 4);
    put(f, "", 1);
    long table = ftell(f), line_bytes = 8 + 16L * width;
    for (int y = 0; y < height; ++y) {
        uint64_t offset = (uint64_t)(table + 8L * height + line_bytes * y);
        put(f, &offset, 8);
    }
    for (int y = 0; y < height; ++y) {
        put_i32(f, y), put_i32(f, 16 * width);
        static const int order[4] = {3, 2, 1, 0};   /* A B G R from RGBA */
        for (int c = 0; c < 4; ++c)
            for (int x = 0; x < width; ++x) put(f, &rgba[4 * ((size_t)y * width + x) + order[c]], 4);
    }
    return fclose(f) == 0 ? 0 : -1;
}

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

void hv_window_create(const hv_device *d, hv_window *w, GLFWwindow *window, VkImageView hdr_view,
                      const uint32_t *vs, size_t vs_size, const uint32_t *fs, size_t fs_size)
{
    memset(w, 0, sizeof *w);
    w->window = window;
    HV_CHECK(glfwCreateWindowSurface(d->instance, window, NULL, &w->surface));
    VkBool32 present = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(d->gpu, d->family, w->surface, &present);
    if (!present) {
        fprintf(stderr, "sky_host: the queue family cannot present to the window\n");
        exit(1);
    }
    VkSurfaceCapabilitiesKHR caps;
    HV_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(d->gpu, w->surface, &caps));
    int fw, fh;
    glfwGetFramebufferSize(window, &fw, &fh);
    w->extent = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : (VkExtent2D){(uint32_t)fw, (uint32_t)fh};
    w->format = VK_FORMAT_B8G8R8A8_SRGB;
    uint32_t images = caps.minImageCount + 1;
    if (caps.maxImageCount && images > caps.maxImageCount) images = caps.maxImageCount;
    VkSwapchainCreateInfoKHR si = {.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR, .surface = w->surface,
                                   .minImageCount = images, .imageFormat = w->format,
                                   .imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR, .imageExtent = w->extent,
                                   .imageArrayLayers = 1, .imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                   .preTransform = caps.currentTransform,
                                   .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
                                   .presentMode = VK_PRESENT_MODE_FIFO_KHR, .clipped = VK_TRUE};
    HV_CHECK(vkCreateSwapchainKHR(d->device, &si, NULL, &w->swapchain));
    w->count = 8;
    HV_CHECK(vkGetSwapchainImagesKHR(d->device, w->swapchain, &w->count, w->images));
    VkSemaphoreCreateInfo semi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    HV_CHECK(vkCreateSemaphore(d->device, &semi, NULL, &w->acquired));
    for (uint32_t i = 0; i < w->count; ++i) {
        VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = w->images[i],
                                    .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = w->format,
                                    .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
        HV_CHECK(vkCreateImageView(d->device, &vi, NULL, &w->views[i]));
        HV_CHECK(vkCreateSemaphore(d->device, &semi, NULL, &w->done[i]));
    }
    /* The tone map: one sampled image, one float of push constants. */
    VkSamplerCreateInfo sa = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_LINEAR,
                              .minFilter = VK_FILTER_LINEAR, .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    HV_CHECK(vkCreateSampler(d->device, &sa, NULL, &w->sampler));
    VkDescriptorSetLayoutBinding b = {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, NULL};
    VkDescriptorSetLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                          .bindingCount = 1, .pBindings = &b};
    HV_CHECK(vkCreateDescriptorSetLayout(d->device, &li, NULL, &w->set_layout));
    VkDescriptorPoolSize ps = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                     .poolSizeCount = 1, .pPoolSizes = &ps};
    HV_CHECK(vkCreateDescriptorPool(d->device, &pi, NULL, &w->pool));
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorPool = w->pool,
                                      .descriptorSetCount = 1, .pSetLayouts = &w->set_layout};
    HV_CHECK(vkAllocateDescriptorSets(d->device, &ai, &w->set));
    VkDescriptorImageInfo ii = {w->sampler, hdr_view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet wr = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = w->set, .descriptorCount = 1,
                               .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .pImageInfo = &ii};
    vkUpdateDescriptorSets(d->device, 1, &wr, 0, NULL);
    VkPushConstantRange pr = {VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(float)};
    VkPipelineLayoutCreateInfo pl = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
                                     .pSetLayouts = &w->set_layout, .pushConstantRangeCount = 1,
                                     .pPushConstantRanges = &pr};
    HV_CHECK(vkCreatePipelineLayout(d->device, &pl, NULL, &w->layout));
    w->tonemap = hv_pipeline(d, w->layout, vs, vs_size, fs, fs_size, w->format, VK_FORMAT_UNDEFINED, false);
}

void hv_window_destroy(const hv_device *d, hv_window *w)
{
    vkDestroyPipeline(d->device, w->tonemap, NULL);
    vkDestroyPipelineLayout(d->device, w->layout, NULL);
    vkDestroyDescriptorPool(d->device, w->pool, NULL);
    vkDestroyDescriptorSetLayout(d->device, w->set_layout, NULL);
    vkDestroySampler(d->device, w->sampler, NULL);
    for (uint32_t i = 0; i < w->count; ++i) {
        vkDestroyImageView(d->device, w->views[i], NULL);
        vkDestroySemaphore(d->device, w->done[i], NULL);
    }
    vkDestroySemaphore(d->device, w->acquired, NULL);
    vkDestroySwapchainKHR(d->device, w->swapchain, NULL);
    vkDestroySurfaceKHR(d->instance, w->surface, NULL);
}

/* One quad (two triangles) of the mesh: corner c, edges u and v, normal n. */
static float *quad(float *o, const double c[3], const double u[3], const double v[3], const double n[3], float albedo)
{
    static const int corners[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 6; ++k, o += 7) {
        for (int i = 0; i < 3; ++i) o[i] = (float)(c[i] + corners[k][0] * u[i] + corners[k][1] * v[i]), o[3 + i] = (float)n[i];
        o[6] = albedo;
    }
    return o;
}

uint32_t hv_mesh_build(float *o)
{
    float *start = o;
    double g = SCENE_GROUND_HALF_M;
    o = quad(o, (double[]){-g, 0, -g}, (double[]){2 * g, 0, 0}, (double[]){0, 0, 2 * g}, (double[]){0, 1, 0},
             SCENE_GROUND_ALBEDO);
    for (int b = 0; b < SCENE_BOX_COUNT; ++b) {
        const scene_box *s = &SCENE_BOXES[b];
        double w = s->width_m, h = s->height_m, x0 = s->x_m - 0.5 * w, z0 = -s->distance_m;   /* front face at z0 */
        o = quad(o, (double[]){x0, 0, z0}, (double[]){w, 0, 0}, (double[]){0, h, 0}, (double[]){0, 0, 1}, s->albedo);
        o = quad(o, (double[]){x0, 0, z0 - w}, (double[]){w, 0, 0}, (double[]){0, h, 0}, (double[]){0, 0, -1}, s->albedo);
        o = quad(o, (double[]){x0, 0, z0 - w}, (double[]){0, 0, w}, (double[]){0, h, 0}, (double[]){-1, 0, 0}, s->albedo);
        o = quad(o, (double[]){x0 + w, 0, z0 - w}, (double[]){0, 0, w}, (double[]){0, h, 0}, (double[]){1, 0, 0}, s->albedo);
        o = quad(o, (double[]){x0, h, z0 - w}, (double[]){w, 0, 0}, (double[]){0, 0, w}, (double[]){0, 1, 0}, s->albedo);
    }
    return (uint32_t)((o - start) / 7);
}

void hv_window_present(const hv_device *d, hv_window *w, VkCommandBuffer cmd, uint32_t index)
{
    /* The swapchain image after the acquire (its semaphore waited at COLOR_ATTACHMENT_OUTPUT, the barrier's source
     * stage), written by the tone map, then handed to presentation. */
    hv_barrier(cmd, w->images[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
               VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo ca = {.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, .imageView = w->views[index],
                                    .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                    .loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE, .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
    VkRenderingInfo ri = {.sType = VK_STRUCTURE_TYPE_RENDERING_INFO, .renderArea = {{0, 0}, w->extent},
                          .layerCount = 1, .colorAttachmentCount = 1, .pColorAttachments = &ca};
    vkCmdBeginRendering(cmd, &ri);
    vkCmdSetViewport(cmd, 0, 1, &(VkViewport){0, 0, (float)w->extent.width, (float)w->extent.height, 0, 1});
    vkCmdSetScissor(cmd, 0, 1, &(VkRect2D){{0, 0}, w->extent});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, w->tonemap);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, w->layout, 0, 1, &w->set, 0, NULL);
    float exposure = 1.0f;
    vkCmdPushConstants(cmd, w->layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof exposure, &exposure);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    hv_barrier(cmd, w->images[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_2_NONE, 0, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    HV_CHECK(vkEndCommandBuffer(cmd));
    VkSemaphoreSubmitInfo wait = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = w->acquired,
                                  .stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT};
    VkSemaphoreSubmitInfo signal = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = w->done[index],
                                    .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = 1,
                        .pWaitSemaphoreInfos = &wait, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi,
                        .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &signal};
    HV_CHECK(vkQueueSubmit2(d->queue, 1, &si, VK_NULL_HANDLE));
    VkPresentInfoKHR pi = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, .waitSemaphoreCount = 1,
                           .pWaitSemaphores = &w->done[index], .swapchainCount = 1, .pSwapchains = &w->swapchain,
                           .pImageIndices = &index};
    vkQueuePresentKHR(d->queue, &pi);
    /* One frame in flight: simple, not fast (an engine keeps two, with a fence each). */
    HV_CHECK(vkQueueWaitIdle(d->queue));
    vkFreeCommandBuffers(d->device, d->pool, 1, &cmd);
}

int hv_write_exr_half(const char *path, const uint16_t *rgba, int width, int height)
{
    size_t n = 4 * (size_t)width * height;
    float *f = malloc(sizeof(float) * n);
    if (!f) return -1;
    for (size_t i = 0; i < n; ++i) f[i] = hv_half_to_float(rgba[i]);
    int r = hv_write_exr(path, f, width, height);
    free(f);
    return r;
}

/* IEC 61966-2-1: what an SRGB image format does to a shader's output on store. */
static uint8_t srgb8(float linear)
{
    float c = linear <= 0.0f ? 0.0f : linear >= 1.0f ? 1.0f : linear;
    float e = c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)lrintf(e * 255.0f);
}

int hv_write_png_tonemapped(const char *path, const uint16_t *rgba, int width, int height, float exposure)
{
    uint8_t *px = malloc(4 * (size_t)width * height);
    FILE *f = px ? fopen(path, "wb") : NULL;
    png_structp png = f ? png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL) : NULL;
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        if (f) fclose(f);
        free(px);
        return -1;
    }
    for (size_t i = 0; i < (size_t)width * height; ++i) {
        for (int c = 0; c < 3; ++c) {
            float v = hv_half_to_float(rgba[4 * i + c]) * exposure;
            px[4 * i + c] = srgb8(v / (1.0f + v));
        }
        px[4 * i + 3] = 255;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y) png_write_row(png, px + 4 * (size_t)y * width);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(px);
    return fclose(f) == 0 ? 0 : -1;
}

void hv_copy_to_host(const hv_device *d, VkCommandBuffer cmd, VkImage image, VkExtent2D extent, const hv_buffer *buffer)
{
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer->buffer, 1, &region);
    /* The copy wrote the buffer; the host reads it after the wait: RAW (the wait alone makes nothing visible). */
    VkMemoryBarrier2 to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT, .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                            .pMemoryBarriers = &to_host};
    vkCmdPipelineBarrier2(cmd, &dep);
    hv_submit_wait(d, cmd);
}
