/* Debug names and labels on the API path (issue 25; vksky_context_set_debug_utils), as a host with RenderDoc sees them.
 * The host hands vksky a vkGetInstanceProcAddr of its own that forwards everything to the loader and wraps the three
 * VK_EXT_debug_utils calls vksky may make, so every name and label vksky gives is read back here:
 * 1. with the host's word (set_debug_utils true): the LUT images, pipelines and buffers are named "vksky.*" (every
 *    name vksky gives starts so), a DISPLAY frame's commands sit under one "vksky.record" label holding a label per
 *    pass (the LUT passes, the sky, the tone map), begin and end balanced; the frame is validation clean (the
 *    validation layer and synchronization validation on);
 * 2. a deliberate validation error on one of vksky's objects (the transmittance LUT's view as an input attachment)
 *    is reported with its vksky name in the message's objects;
 * 3. without it (a host whose instance lacks the extension): not one debug-utils call, the frame still clean. */
#include "api_host.h"

enum { MAX_NAMES = 512, MAX_LABELS = 128 };
static struct { VkObjectType type; char name[96]; } names[MAX_NAMES];
static unsigned name_count, begin_count, end_count, depth, max_depth;
static char labels[MAX_LABELS][64];
static unsigned label_count;

static PFN_vkSetDebugUtilsObjectNameEXT real_set_name;
static PFN_vkCmdBeginDebugUtilsLabelEXT real_begin;
static PFN_vkCmdEndDebugUtilsLabelEXT real_end;

static VKAPI_ATTR VkResult VKAPI_CALL wrap_set_name(VkDevice device, const VkDebugUtilsObjectNameInfoEXT *info)
{
    if (name_count < MAX_NAMES) {
        names[name_count].type = info->objectType;
        snprintf(names[name_count].name, sizeof names[0].name, "%s", info->pObjectName ? info->pObjectName : "");
    }
    name_count++;
    return real_set_name(device, info);
}

static VKAPI_ATTR void VKAPI_CALL wrap_begin(VkCommandBuffer cmd, const VkDebugUtilsLabelEXT *label)
{
    if (label_count < MAX_LABELS) snprintf(labels[label_count++], sizeof labels[0], "%s", label->pLabelName);
    begin_count++;
    if (++depth > max_depth) max_depth = depth;
    real_begin(cmd, label);
}

static VKAPI_ATTR void VKAPI_CALL wrap_end(VkCommandBuffer cmd)
{
    end_count++;
    depth--;
    real_end(cmd);
}

static VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL host_gipa(VkInstance instance, const char *name)
{
    PFN_vkVoidFunction real = vkGetInstanceProcAddr(instance, name);
    if (!real || !instance) return real;
    if (!strcmp(name, "vkSetDebugUtilsObjectNameEXT")) {
        real_set_name = (PFN_vkSetDebugUtilsObjectNameEXT)real;
        return (PFN_vkVoidFunction)wrap_set_name;
    }
    if (!strcmp(name, "vkCmdBeginDebugUtilsLabelEXT")) {
        real_begin = (PFN_vkCmdBeginDebugUtilsLabelEXT)real;
        return (PFN_vkVoidFunction)wrap_begin;
    }
    if (!strcmp(name, "vkCmdEndDebugUtilsLabelEXT")) {
        real_end = (PFN_vkCmdEndDebugUtilsLabelEXT)real;
        return (PFN_vkVoidFunction)wrap_end;
    }
    return real;
}

static bool named(VkObjectType type, const char *name)
{
    for (unsigned i = 0; i < name_count && i < MAX_NAMES; ++i)
        if (names[i].type == type && !strcmp(names[i].name, name)) return true;
    return false;
}

static bool labelled(const char *name)
{
    for (unsigned i = 0; i < label_count; ++i)
        if (!strcmp(labels[i], name)) return true;
    return false;
}

/* The deliberate error's messages: how many, and how many name vksky's object. */
static unsigned error_messages, error_named;
static VKAPI_ATTR VkBool32 VKAPI_CALL error_debug(VkDebugUtilsMessageSeverityFlagBitsEXT s,
                                                  VkDebugUtilsMessageTypeFlagsEXT t,
                                                  const VkDebugUtilsMessengerCallbackDataEXT *d, void *u)
{
    (void)s, (void)t, (void)u;
    error_messages++;
    /* The layer names the object in its objects list or in the text ("VkImageView 0x...[name]"). */
    if (d->pMessage && strstr(d->pMessage, "[vksky.transmittance_lut]")) {
        error_named++;
        return VK_FALSE;
    }
    for (uint32_t i = 0; i < d->objectCount; ++i)
        if (d->pObjects[i].pObjectName && !strcmp(d->pObjects[i].pObjectName, "vksky.transmittance_lut")) {
            error_named++;
            break;
        }
    return VK_FALSE;
}

static void reset_counts(void) { name_count = begin_count = end_count = depth = max_depth = label_count = 0; }

/* One DISPLAY frame into the host's image, submitted and waited for. */
static void one_frame(host *h, vksky_renderer *r)
{
    vksky_camera cam = {.position_m = {0, 2, 0}};
    vksky_camera_look(&cam, 0.0, 10.0, 60.0, (double)h->width / h->height, 0.1);
    vksky_frame f = {.camera = &cam, .exposure = 12.0, .color = host_image(h, VK_FORMAT_R8G8B8A8_SRGB)};
    host_begin(h);
    vksky_result res = vksky_record(r, h->cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
    host_end_submit_wait(h);
}

int main(void)
{
    host h;
    host_create_device(&h, NULL);
    host_create_target(&h, 64, 48, VK_FORMAT_R8G8B8A8_SRGB);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    cd.get_instance_proc_addr = host_gipa;
    vksky_renderer_desc rd = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = 64,
                              .height = 48, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "low",
                              .units = VKSKY_UNITS_PHOTOMETRIC};

    /* 1. Names and labels with the host's word. */
    vksky_context *c = NULL;
    HOST_CHECK(vksky_context_create(&cd, &c) == VKSKY_SUCCESS && c, "vksky_context_create");
    if (!c) return 1;
    HOST_CHECK(vksky_context_set_debug_utils(c, true) == VKSKY_SUCCESS, "vksky_context_set_debug_utils");
    reset_counts();
    vksky_renderer *r = host_renderer(c, &rd);
    HOST_CHECK(vksky_context_set_debug_utils(c, false) == VKSKY_ERROR_INVALID_ARGUMENT,
               "set_debug_utils after a renderer was made: refused");
    one_frame(&h, r);
    printf("names %u, labels %u (depth %u):", name_count, begin_count, max_depth);
    for (unsigned i = 0; i < label_count; ++i) printf(" %s", labels[i]);
    printf("\n");
    HOST_CHECK(named(VK_OBJECT_TYPE_IMAGE, "vksky.transmittance_lut"), "the transmittance LUT is named");
    HOST_CHECK(named(VK_OBJECT_TYPE_IMAGE, "vksky.multiscatter_lut"), "the multi-scattering LUT is named");
    HOST_CHECK(named(VK_OBJECT_TYPE_IMAGE, "vksky.skyview_lut"), "the sky-view LUT is named");
    HOST_CHECK(named(VK_OBJECT_TYPE_IMAGE_VIEW, "vksky.transmittance_lut"), "its view is named");
    unsigned pipelines = 0, buffers = 0, unprefixed = 0;
    for (unsigned i = 0; i < name_count && i < MAX_NAMES; ++i) {
        pipelines += names[i].type == VK_OBJECT_TYPE_PIPELINE;
        buffers += names[i].type == VK_OBJECT_TYPE_BUFFER;
        if (strncmp(names[i].name, "vksky.", 6) || strchr(names[i].name, ' ')) {
            unprefixed++;
            fprintf(stderr, "name without the prefix: \"%s\"\n", names[i].name);
        }
    }
    HOST_CHECK(pipelines >= 4 && buffers >= 1, "pipelines named %u, buffers named %u", pipelines, buffers);
    HOST_CHECK(unprefixed == 0, "%u names without \"vksky.\"", unprefixed);
    HOST_CHECK(label_count > 0 && !strcmp(labels[0], "vksky.record"), "the frame opens with vksky.record");
    HOST_CHECK(labelled("transmittance_lut") && labelled("multiscatter_lut") && labelled("skyview_lut") &&
               labelled("sky") && labelled("tonemap"), "a label per pass (the three LUTs, sky, tonemap)");
    HOST_CHECK(begin_count == end_count && depth == 0 && max_depth == 2,
               "labels balanced: %u begins, %u ends, depth %u at most", begin_count, end_count, max_depth);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages in the labelled frame", host_validation_messages);

    /* 2. A deliberate error on vksky's object: the layer names it. */
    PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
        (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h.instance, "vkCreateDebugUtilsMessengerEXT");
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger =
        (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(h.instance, "vkDestroyDebugUtilsMessengerEXT");
    VkDebugUtilsMessengerCreateInfoEXT mi = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT, .pfnUserCallback = error_debug};
    VkDebugUtilsMessengerEXT errors;
    HOST_VK(create_messenger(h.instance, &mi, NULL, &errors));
    vksky_luts luts;
    HOST_CHECK(vksky_get_luts(r, &luts) == VKSKY_SUCCESS, "vksky_get_luts");
    unsigned before = host_validation_messages;
    /* The LUT's view was made for sampling and storage: written as an input attachment it breaks a VUID of
     * vkUpdateDescriptorSets (the layer skips the call: nothing reaches the driver). */
    VkDescriptorSetLayoutBinding b = {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT,
                                      .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT};
    VkDescriptorSetLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                          .bindingCount = 1, .pBindings = &b};
    VkDescriptorSetLayout set_layout;
    HOST_VK(vkCreateDescriptorSetLayout(h.device, &li, NULL, &set_layout));
    VkDescriptorPoolSize ps = {VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1};
    VkDescriptorPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                     .poolSizeCount = 1, .pPoolSizes = &ps};
    VkDescriptorPool pool;
    HOST_VK(vkCreateDescriptorPool(h.device, &pi, NULL, &pool));
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, .descriptorPool = pool,
                                      .descriptorSetCount = 1, .pSetLayouts = &set_layout};
    VkDescriptorSet set;
    HOST_VK(vkAllocateDescriptorSets(h.device, &ai, &set));
    VkDescriptorImageInfo ii = {.imageView = luts.transmittance, .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = 0,
                              .descriptorCount = 1, .descriptorType = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT,
                              .pImageInfo = &ii};
    vkUpdateDescriptorSets(h.device, 1, &w, 0, NULL);
    vkDestroyDescriptorPool(h.device, pool, NULL);
    vkDestroyDescriptorSetLayout(h.device, set_layout, NULL);
    destroy_messenger(h.instance, errors, NULL);
    printf("deliberate error: %u messages, %u naming vksky.transmittance_lut\n", error_messages, error_named);
    HOST_CHECK(error_messages > 0 && error_named > 0, "the deliberate error names vksky.transmittance_lut (%u of %u)",
               error_named, error_messages);
    host_validation_messages = before;   /* those were the deliberate ones */
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);

    /* 3. No word from the host: no call at all. */
    reset_counts();
    HOST_CHECK(vksky_context_create(&cd, &c) == VKSKY_SUCCESS && c, "vksky_context_create (no debug utils)");
    if (!c) return 1;
    r = host_renderer(c, &rd);
    one_frame(&h, r);
    HOST_CHECK(name_count == 0 && begin_count == 0 && end_count == 0,
               "without set_debug_utils: %u names, %u begins, %u ends", name_count, begin_count, end_count);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    vksky_renderer_destroy(r);
    vksky_context_destroy(c);

    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    if (host_failures) return 1;
    printf("api_labels: ok\n");
    return 0;
}
