/* A minimal host for the API tests: its own instance (validation + synchronization validation, every message
 * counted), a device with a graphics+compute queue of its choosing, an 8-bit colour image vksky writes and a buffer
 * it is read back through. Written against the Vulkan loader directly (libvulkan), as a host engine would be: it
 * shares no code with vksky. */
#ifndef VKSKY_API_HOST_H
#define VKSKY_API_HOST_H
#ifndef VOLK_H_
#include <vulkan/vulkan.h>   /* a host on the loader; the drop probe, built from vksky's objects, is on volk */
#endif
#include <vksky.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef VKSKY_SANITIZE
#include <dlfcn.h>
#endif

static int host_failures __attribute__((unused));
#define HOST_CHECK(cond, ...)                                                                               \
    do {                                                                                                    \
        if (!(cond)) {                                                                                      \
            ++host_failures;                                                                                \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                 \
            fprintf(stderr, __VA_ARGS__);                                                                   \
            fputc('\n', stderr);                                                                            \
        }                                                                                                   \
    } while (0)
#define HOST_VK(call)                                                                                       \
    do {                                                                                                    \
        VkResult host_r_ = (call);                                                                          \
        if (host_r_ != VK_SUCCESS) { fprintf(stderr, "FAIL %s:%d: %s: %d\n", __FILE__, __LINE__, #call, host_r_); exit(1); } \
    } while (0)

static unsigned host_validation_messages;
static unsigned host_result_messages;   /* of those, the layer's report of a call's failing VkResult (its name alone) */
static VKAPI_ATTR VkBool32 VKAPI_CALL host_debug(VkDebugUtilsMessageSeverityFlagBitsEXT s,
                                                 VkDebugUtilsMessageTypeFlagsEXT t,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *d, void *u)
{
    (void)s, (void)t, (void)u;
    host_validation_messages++;
    if (d->pMessage && !strncmp(d->pMessage, "VK_ERROR_", 9) && !strchr(d->pMessage, ' ')) host_result_messages++;
    /* The CLI's words, so that tests/barrier_drop_test.sh reads the drop probe's messages as it reads vksky's
     * (with the id in front where a newer layer leaves it out of the text, as src/gpu/context.c does). */
    const char *id = d->pMessageIdName, *text = d->pMessage ? d->pMessage : "(no text)";
    if (id && *id && !strstr(text, id)) fprintf(stderr, "vksky: validation error: [ %s ] %s\n", id, text);
    else fprintf(stderr, "vksky: validation error: %s\n", text);
    return VK_FALSE;
}

/* vksky's messages: validation ones counted (a context vksky made), everything printed for the log. */
static unsigned api_messages[4];
static inline void api_message(void *user, vksky_severity severity, const char *text)
{
    (void)user;
    api_messages[severity]++;
    fprintf(stderr, "vksky message (%d): %s\n", (int)severity, text);
}

typedef struct host {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical;
    VkDevice device;
    uint32_t family, index;
    VkQueue queue;
    uint32_t compute_family;        /* host_want_compute_family: a compute-only family's queue 0, else UINT32_MAX */
    VkQueue compute_queue;
    bool owns;                      /* made here (else vksky's own context's handles) */
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    uint32_t width, height;
    VkImage image;
    VkImageView view;
    VkDeviceMemory image_memory, buffer_memory;
    VkBuffer buffer;
    void *mapped;
} host;

static inline uint32_t host_memory_type(const host *h, uint32_t bits, VkMemoryPropertyFlags want)
{
    VkPhysicalDeviceMemoryProperties m;
    vkGetPhysicalDeviceMemoryProperties(h->physical, &m);
    for (uint32_t i = 0; i < m.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (m.memoryTypes[i].propertyFlags & want) == want) return i;
    fprintf(stderr, "FAIL: no memory type\n");
    exit(1);
}

/* Set before host_create_device: the device also gets queue 0 of a compute-only family when it has one
 * (api_qfot_probe: the LUTs' queue-family ownership transfer). */
static bool host_want_compute_family __attribute__((unused));

/* The host's own device: Vulkan 1.3 with vksky's requirements, the queue family `family` (its last queue). */
static inline void host_create_device(host *h, const VkAllocationCallbacks *allocator)
{
    memset(h, 0, sizeof *h);
    h->owns = true;
    h->compute_family = UINT32_MAX;
#ifdef VKSKY_SANITIZE
    /* As src/gpu/context.c does: the driver and the layer stay mapped at exit, so tests/lsan.supp can name their own
     * leaks by library instead of an unknown frame that could hide one of ours. */
    const char *libs[] = {"libvulkan.so.1", "libvulkan_lvp.so", "libVkLayer_khronos_validation.so"};
    for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i) dlopen(libs[i], RTLD_LAZY | RTLD_NODELETE);
#endif
    const char *layer = "VK_LAYER_KHRONOS_validation", *ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                        .enabledValidationFeatureCount = 1, .pEnabledValidationFeatures = &sync};
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "vksky api test",
                             .apiVersion = VK_API_VERSION_1_3};
    /* API_HOST_NO_VALIDATION=1: no layer (a measurement of vksky alone, e.g. the resident set over many renderers:
     * the layer's own tracking grows with every object ever made). The tests never set it. */
    bool layer_on = !getenv("API_HOST_NO_VALIDATION");
    VkInstanceCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pNext = layer_on ? &features : NULL,
                               .pApplicationInfo = &app, .enabledLayerCount = layer_on, .ppEnabledLayerNames = &layer,
                               .enabledExtensionCount = 1, .ppEnabledExtensionNames = &ext};
    HOST_VK(vkCreateInstance(&ii, NULL, &h->instance));
#ifdef VOLK_H_
    volkLoadInstance(h->instance);
#endif
    PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h->instance, "vkCreateDebugUtilsMessengerEXT");
    VkDebugUtilsMessengerCreateInfoEXT mi = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
        .pfnUserCallback = host_debug};
    HOST_VK(create_messenger(h->instance, &mi, NULL, &h->messenger));
    uint32_t n = 1;
    vkEnumeratePhysicalDevices(h->instance, &n, &h->physical);   /* the first device (VK_INCOMPLETE is fine) */
    /* The host's choice of queue: the last graphics+compute family, its last queue. */
    VkQueueFamilyProperties q[16];
    uint32_t qn = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(h->physical, &qn, q);
    for (uint32_t i = 0; i < qn; ++i)
        if ((q[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))
            h->family = i, h->index = q[i].queueCount - 1;
    float priorities[16] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    VkDeviceQueueCreateInfo qi[2] = {{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueFamilyIndex = h->family,
                                      .queueCount = h->index + 1, .pQueuePriorities = priorities}};
    for (uint32_t i = 0; host_want_compute_family && i < qn && h->compute_family == UINT32_MAX; ++i)
        if ((q[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == VK_QUEUE_COMPUTE_BIT && q[i].queueCount)
            h->compute_family = i;
    if (h->compute_family != UINT32_MAX)
        qi[1] = (VkDeviceQueueCreateInfo){.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                          .queueFamilyIndex = h->compute_family, .queueCount = 1,
                                          .pQueuePriorities = priorities};
    vksky_device_requirements req;
    vksky_get_device_requirements(&req);
    VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                            .synchronization2 = req.synchronization2,
                                            .dynamicRendering = req.dynamic_rendering, .maintenance4 = VK_TRUE};
    /* Timeline semaphores (core 1.2): the host's own, around vksky_record_luts (api_async). */
    VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                            .timelineSemaphore = VK_TRUE};
    f13.pNext = &f12;
    VkDeviceCreateInfo di = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &f13,
                             .queueCreateInfoCount = h->compute_family != UINT32_MAX ? 2 : 1, .pQueueCreateInfos = qi};
    HOST_VK(vkCreateDevice(h->physical, &di, allocator, &h->device));
    vkGetDeviceQueue(h->device, h->family, h->index, &h->queue);
    if (h->compute_family != UINT32_MAX) vkGetDeviceQueue(h->device, h->compute_family, 0, &h->compute_queue);
}

/* vksky's own context's device, used as a host would use its own. */
static inline void host_from_context(host *h, const vksky_context *c)
{
    memset(h, 0, sizeof *h);
    vksky_context_handles hd;
    vksky_context_get_handles(c, &hd);
    h->instance = hd.instance, h->physical = hd.physical_device, h->device = hd.device, h->queue = hd.queue;
    h->family = hd.queue_family;
}

/* vksky's own device with validation + synchronization validation on, its messages to api_message (the tests that
 * need no device of their own). A failure is counted and ends the test. */
static inline vksky_context *host_own_context(void)
{
    vksky_own_device_desc od = {.abi_version = VKSKY_ABI_VERSION, .device_index = -1, .validation = true,
                                .message = api_message};
    vksky_context *c = NULL;
    vksky_result res = vksky_context_create_own(&od, &c);
    HOST_CHECK(res == VKSKY_SUCCESS && c, "vksky_context_create_own: %s", vksky_result_name(res));
    if (!c) exit(1);
    return c;
}

/* The scene of a command line (vksky_scene_from_args); a failure is counted and ends the test. */
static inline vksky_scene *host_scene_of_args(int argc, char **argv)
{
    vksky_scene *scene = NULL;
    vksky_result res = vksky_scene_from_args(argc, argv, api_message, NULL, &scene);
    HOST_CHECK(res == VKSKY_SUCCESS && scene, "vksky_scene_from_args: %s", vksky_result_name(res));
    if (!scene) exit(1);
    return scene;
}

/* The renderer `vksky --render` makes (the CLI's own host: app/runs/headless_api.c): DISPLAY read back into vksky's
 * own images (rb, the caller's), photometric, the quality the command line's scene chose. */
static inline vksky_renderer_desc host_readback_desc(const vksky_readback_config *rb, const vksky_scene *scene,
                                                     uint32_t width, uint32_t height, bool bloom)
{
    return (vksky_renderer_desc){.abi_version = VKSKY_ABI_VERSION, .next = rb, .output = VKSKY_OUTPUT_DISPLAY,
                                 .width = width, .height = height, .target_format = VK_FORMAT_R8G8B8A8_SRGB,
                                 .quality = "scene", .bloom = bloom, .units = VKSKY_UNITS_PHOTOMETRIC, .scene = scene};
}

/* A renderer of `d`; a failure is counted and ends the test. */
static inline vksky_renderer *host_renderer(vksky_context *c, const vksky_renderer_desc *d)
{
    vksky_renderer *r = NULL;
    vksky_result res = vksky_renderer_create(c, d, &r);
    HOST_CHECK(res == VKSKY_SUCCESS && r, "vksky_renderer_create %ux%u: %s", d->width, d->height, vksky_result_name(res));
    if (!r) exit(1);
    return r;
}

static inline vksky_context_desc host_context_desc(const host *h, const VkAllocationCallbacks *allocator)
{
    return (vksky_context_desc){.abi_version = VKSKY_ABI_VERSION, .get_instance_proc_addr = vkGetInstanceProcAddr,
                                .instance = h->instance, .physical_device = h->physical, .device = h->device,
                                .queue_family = h->family, .queue_index = h->index, .allocator = allocator,
                                .message = api_message};
}

/* The target image (colour attachment + copy source, + `extra` usage) and its readback buffer. */
static inline void host_create_target_usage(host *h, uint32_t width, uint32_t height, VkFormat format,
                                            VkImageUsageFlags extra)
{
    h->width = width, h->height = height;
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {width, height, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | extra};
    HOST_VK(vkCreateImage(h->device, &ii, NULL, &h->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(h->device, h->image, &req);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = host_memory_type(h, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)};
    HOST_VK(vkAllocateMemory(h->device, &ai, NULL, &h->image_memory));
    HOST_VK(vkBindImageMemory(h->device, h->image, h->image_memory, 0));
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = h->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    HOST_VK(vkCreateImageView(h->device, &vi, NULL, &h->view));
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 4ull * width * height,
                             .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    HOST_VK(vkCreateBuffer(h->device, &bi, NULL, &h->buffer));
    vkGetBufferMemoryRequirements(h->device, h->buffer, &req);
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = host_memory_type(h, req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                     VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    HOST_VK(vkAllocateMemory(h->device, &ai, NULL, &h->buffer_memory));
    HOST_VK(vkBindBufferMemory(h->device, h->buffer, h->buffer_memory, 0));
    HOST_VK(vkMapMemory(h->device, h->buffer_memory, 0, VK_WHOLE_SIZE, 0, &h->mapped));
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, .queueFamilyIndex = h->family};
    HOST_VK(vkCreateCommandPool(h->device, &pi, NULL, &h->pool));
    VkCommandBufferAllocateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = h->pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    HOST_VK(vkAllocateCommandBuffers(h->device, &ci, &h->cmd));
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    HOST_VK(vkCreateFence(h->device, &fi, NULL, &h->fence));
}

static inline void host_create_target(host *h, uint32_t width, uint32_t height, VkFormat format)
{
    host_create_target_usage(h, width, height, format, 0);
}

static inline void host_begin(host *h)
{
    HOST_VK(vkResetCommandBuffer(h->cmd, 0));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    HOST_VK(vkBeginCommandBuffer(h->cmd, &bi));
}

/* Ends the command buffer host_begin began, submits it alone and waits for it (the tests' one-frame round trip). */
static inline void host_end_submit_wait(host *h)
{
    HOST_VK(vkEndCommandBuffer(h->cmd));
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = h->cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1, .pCommandBufferInfos = &ci};
    HOST_VK(vkQueueSubmit2(h->queue, 1, &si, h->fence));
    HOST_VK(vkWaitForFences(h->device, 1, &h->fence, VK_TRUE, UINT64_MAX));
    HOST_VK(vkResetFences(h->device, 1, &h->fence));
}

/* The host's frame: vksky leaves the image ready for a transfer read; the host copies it and waits. */
static inline vksky_image host_image(const host *h, VkFormat format)
{
    return (vksky_image){
        .image = h->image, .view = h->view, .format = format, .extent = {h->width, h->height},
        .before = {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED},
        .after = {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}};
}

/* The host's copy of vksky's image into its buffer, recorded. */
static inline void host_copy(host *h)
{
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {h->width, h->height, 1}};
    vkCmdCopyImageToBuffer(h->cmd, h->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, h->buffer, 1, &region);
}

static inline void host_submit(host *h, VkBuffer readback);

static inline void host_end_and_read(host *h)
{
    host_copy(h);
    host_submit(h, h->buffer);
}

static inline void host_destroy_target(host *h)
{
    vkDeviceWaitIdle(h->device);
    vkDestroyFence(h->device, h->fence, NULL);
    vkDestroyCommandPool(h->device, h->pool, NULL);
    vkDestroyBuffer(h->device, h->buffer, NULL);
    vkFreeMemory(h->device, h->buffer_memory, NULL);
    vkDestroyImageView(h->device, h->view, NULL);
    vkDestroyImage(h->device, h->image, NULL);
    vkFreeMemory(h->device, h->image_memory, NULL);
}

static inline void host_destroy_device(host *h, const VkAllocationCallbacks *allocator)
{
    if (!h->owns) return;
    vkDestroyDevice(h->device, allocator);
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger =
        (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h->instance, "vkDestroyDebugUtilsMessengerEXT");
    destroy_messenger(h->instance, h->messenger, NULL);
    vkDestroyInstance(h->instance, NULL);
}

/* The host's own pass over vksky's LUTs (VKSKY_OUTPUT_LUTS_ONLY): a compute shader built on include/vksky_luts.glsl
 * (tests/api/consumer/luts_host.comp) writes an RGBA32F image of `width` x 3 texels, copied to a host buffer. */
typedef struct host_luts {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkImage image;
    VkImageView view;
    VkDeviceMemory image_memory, buffer_memory;
    VkBuffer buffer;
    const float *texels;          /* width x 3 RGBA floats after host_luts_end_and_read */
    uint32_t width;
    float radii[4];
} host_luts;

static inline void host_luts_create(host *h, host_luts *l, const vksky_luts *luts, const uint32_t *spv, size_t spv_size,
                                    uint32_t width)
{
    memset(l, 0, sizeof *l);
    l->width = width;
    l->radii[0] = luts->bottom_radius_km, l->radii[1] = luts->top_radius_km;
    VkDescriptorSetLayoutBinding b[4];
    for (uint32_t i = 0; i < 4; ++i)
        b[i] = (VkDescriptorSetLayoutBinding){i, i < 3 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                              1, VK_SHADER_STAGE_COMPUTE_BIT, NULL};
    VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 4, .pBindings = b};
    HOST_VK(vkCreateDescriptorSetLayout(h->device, &sli, NULL, &l->set_layout));
    VkPushConstantRange pc = {VK_SHADER_STAGE_COMPUTE_BIT, 0, 16};
    VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
                                      .pSetLayouts = &l->set_layout, .pushConstantRangeCount = 1, .pPushConstantRanges = &pc};
    HOST_VK(vkCreatePipelineLayout(h->device, &pli, NULL, &l->layout));
    VkShaderModuleCreateInfo mi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = spv_size, .pCode = spv};
    VkShaderModule module;
    HOST_VK(vkCreateShaderModule(h->device, &mi, NULL, &module));
    VkComputePipelineCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, .layout = l->layout,
                                      .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                                .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = module, .pName = "main"}};
    HOST_VK(vkCreateComputePipelines(h->device, VK_NULL_HANDLE, 1, &ci, NULL, &l->pipeline));
    vkDestroyShaderModule(h->device, module, NULL);
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    VkDescriptorPoolCreateInfo poi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                      .poolSizeCount = 2, .pPoolSizes = sizes};
    HOST_VK(vkCreateDescriptorPool(h->device, &poi, NULL, &l->pool));
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorPool = l->pool,
                                      .descriptorSetCount = 1, .pSetLayouts = &l->set_layout};
    HOST_VK(vkAllocateDescriptorSets(h->device, &ai, &l->set));
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = VK_FORMAT_R32G32B32A32_SFLOAT, .extent = {width, 3, 1}, .mipLevels = 1,
                            .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT};
    HOST_VK(vkCreateImage(h->device, &ii, NULL, &l->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(h->device, l->image, &req);
    VkMemoryAllocateInfo mai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                                .memoryTypeIndex = host_memory_type(h, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)};
    HOST_VK(vkAllocateMemory(h->device, &mai, NULL, &l->image_memory));
    HOST_VK(vkBindImageMemory(h->device, l->image, l->image_memory, 0));
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = l->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = VK_FORMAT_R32G32B32A32_SFLOAT,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    HOST_VK(vkCreateImageView(h->device, &vi, NULL, &l->view));
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 16ull * width * 3,
                             .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    HOST_VK(vkCreateBuffer(h->device, &bi, NULL, &l->buffer));
    vkGetBufferMemoryRequirements(h->device, l->buffer, &req);
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = host_memory_type(h, req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                      VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    HOST_VK(vkAllocateMemory(h->device, &mai, NULL, &l->buffer_memory));
    HOST_VK(vkBindBufferMemory(h->device, l->buffer, l->buffer_memory, 0));
    void *mapped;
    HOST_VK(vkMapMemory(h->device, l->buffer_memory, 0, VK_WHOLE_SIZE, 0, &mapped));
    l->texels = mapped;
    VkDescriptorImageInfo lut[3] = {{luts->sampler, luts->transmittance, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                    {luts->sampler, luts->multiscatter, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                    {luts->sampler, luts->skyview, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    VkDescriptorImageInfo out = {VK_NULL_HANDLE, l->view, VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet w[2] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = l->set, .dstBinding = 0, .descriptorCount = 3,
         .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, .pImageInfo = lut},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = l->set, .dstBinding = 3, .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &out}};
    vkUpdateDescriptorSets(h->device, 2, w, 0, NULL);
}

static inline void host_image_barrier(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags2 ss, VkAccessFlags2 sa,
                                      VkPipelineStageFlags2 ds, VkAccessFlags2 da, VkImageLayout from, VkImageLayout to)
{
    VkImageMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .srcStageMask = ss, .srcAccessMask = sa,
                               .dstStageMask = ds, .dstAccessMask = da, .oldLayout = from, .newLayout = to,
                               .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                               .image = image, .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                            .pImageMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}

/* The host's pass after vksky_record (which left the LUTs ready for vksky_luts.ready_stage/ready_access): its
 * output image rewritten (after the previous copy read it), then copied. */
static inline void host_luts_record(host *h, host_luts *l)
{
    host_image_barrier(h->cmd, l->image, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdBindPipeline(h->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->pipeline);
    vkCmdBindDescriptorSets(h->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->layout, 0, 1, &l->set, 0, NULL);
    vkCmdPushConstants(h->cmd, l->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 16, l->radii);
    vkCmdDispatch(h->cmd, (l->width + 63) / 64, 1, 1);
    host_image_barrier(h->cmd, l->image, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {l->width, 3, 1}};
    vkCmdCopyImageToBuffer(h->cmd, l->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, l->buffer, 1, &region);
}

/* The host's own barrier between two frames' copies into one buffer (WAW). */
static inline void host_buffer_waw(host *h, VkBuffer buffer)
{
    VkBufferMemoryBarrier2 waw = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2, .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                  .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT, .dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                  .dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                  .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .buffer = buffer, .size = VK_WHOLE_SIZE};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1,
                            .pBufferMemoryBarriers = &waw};
    vkCmdPipelineBarrier2(h->cmd, &dep);
}

/* The host's end of the frame: its buffer made visible to its reads after the fence (RAW), submitted waiting for
 * `wait` >= `value` at `stage` (none when VK_NULL_HANDLE), waited. */
static inline void host_submit_waiting(host *h, VkBuffer readback, VkSemaphore wait, uint64_t value,
                                       VkPipelineStageFlags2 stage)
{
    VkBufferMemoryBarrier2 to_host = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                                      .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                      .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                      .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT, .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT,
                                      .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .buffer = readback,
                                      .size = VK_WHOLE_SIZE};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 1,
                            .pBufferMemoryBarriers = &to_host};
    vkCmdPipelineBarrier2(h->cmd, &dep);
    HOST_VK(vkEndCommandBuffer(h->cmd));
    VkSemaphoreSubmitInfo w = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = wait, .value = value,
                               .stageMask = stage};
    VkCommandBufferSubmitInfo ci = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = h->cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = wait ? 1 : 0,
                        .pWaitSemaphoreInfos = &w, .commandBufferInfoCount = 1, .pCommandBufferInfos = &ci};
    HOST_VK(vkQueueSubmit2(h->queue, 1, &si, h->fence));
    HOST_VK(vkWaitForFences(h->device, 1, &h->fence, VK_TRUE, UINT64_MAX));
    HOST_VK(vkResetFences(h->device, 1, &h->fence));
}

/* The host's end of the frame without a semaphore to wait for. */
static inline void host_submit(host *h, VkBuffer readback) { host_submit_waiting(h, readback, VK_NULL_HANDLE, 0, 0); }

static inline void host_luts_destroy(host *h, host_luts *l)
{
    vkDeviceWaitIdle(h->device);
    vkDestroyBuffer(h->device, l->buffer, NULL);
    vkFreeMemory(h->device, l->buffer_memory, NULL);
    vkDestroyImageView(h->device, l->view, NULL);
    vkDestroyImage(h->device, l->image, NULL);
    vkFreeMemory(h->device, l->image_memory, NULL);
    vkDestroyDescriptorPool(h->device, l->pool, NULL);
    vkDestroyPipeline(h->device, l->pipeline, NULL);
    vkDestroyPipelineLayout(h->device, l->layout, NULL);
    vkDestroyDescriptorSetLayout(h->device, l->set_layout, NULL);
}
#endif
