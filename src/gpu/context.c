#include "gpu/context.h"
#include "gpu/barrier.h"
#include "gpu/queue_choice.h"
#include <stdarg.h>
#include <stdatomic.h>
#ifdef VKSKY_SANITIZE
#include <dlfcn.h>
#endif
#include <stdlib.h>
#include <string.h>
#include <time.h>

static atomic_uint validation_messages;

unsigned gpu_validation_message_count(void) { return atomic_load(&validation_messages); }


void gpu_report(const gpu_context *ctx, int severity, const char *format, ...)
{
    char text[512];
    va_list args;
    va_start(args, format);
    vsnprintf(text, sizeof text, format, args);
    va_end(args);
    if (ctx && ctx->message) ctx->message(ctx->message_user, severity, text);
    else fprintf(stderr, "vksky: %s\n", text);
}

/* Every message of the validation layer is printed and counted; a run with any message exits non-zero
 * (the caller checks the count). Loader chatter comes through the loader, not this callback. */
static VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT types,
                                                     const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)types;
    gpu_context *ctx = user;
    atomic_fetch_add(&validation_messages, 1);
    const char *level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT     ? "error"
                        : severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT ? "warning"
                                                                                      : "info";
    if (ctx) ctx->validation_messages++;
    /* Layers up to 1.3.2xx put "[ <message id> ]" into pMessage; newer ones (docs/synchronization.md §14, "What a
     * newer layer sees") pass it only as pMessageIdName. Prefix it then, so every message names its id. */
    const char *text = data->pMessage ? data->pMessage : "(no text)";
    char *tagged = NULL;
    const char *id = data->pMessageIdName;
    if (id && *id && !strstr(text, id) && (tagged = malloc(strlen(id) + strlen(text) + 6)))
        sprintf(tagged, "[ %s ] %s", id, text);
    if (tagged) text = tagged;
    if (ctx && ctx->message) ctx->message(ctx->message_user, 3, text);
    else fprintf(stderr, "vksky: validation %s: %s\n", level, text);
    free(tagged);
    return VK_FALSE;
}

static bool has_layer(const char *name)
{
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, NULL);
    VkLayerProperties *layers = calloc(n ? n : 1, sizeof *layers);
    vkEnumerateInstanceLayerProperties(&n, layers);
    bool found = false;
    for (uint32_t i = 0; i < n; ++i) found |= strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static bool has_device_extension(VkPhysicalDevice physical, const char *name)
{
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(physical, NULL, &n, NULL);
    VkExtensionProperties *ext = calloc(n ? n : 1, sizeof *ext);
    vkEnumerateDeviceExtensionProperties(physical, NULL, &n, ext);
    bool found = false;
    for (uint32_t i = 0; ext && i < n; ++i) found |= strcmp(ext[i].extensionName, name) == 0;
    free(ext);
    return found;
}

static bool has_instance_extension(const char *name)
{
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(NULL, &n, NULL);
    VkExtensionProperties *ext = calloc(n ? n : 1, sizeof *ext);
    vkEnumerateInstanceExtensionProperties(NULL, &n, ext);
    bool found = false;
    for (uint32_t i = 0; i < n; ++i) found |= strcmp(ext[i].extensionName, name) == 0;
    free(ext);
    return found;
}

static int device_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

static const char *device_type_name(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

/* A queue family that does graphics and compute (the spec guarantees one exists if either does). */
static int find_queue_family(VkPhysicalDevice pd)
{
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, NULL);
    VkQueueFamilyProperties q[16];
    if (n > 16) n = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, q);
    for (uint32_t i = 0; i < n; ++i)
        if ((q[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
            (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))
            return (int)i;
    return -1;
}

static bool device_is_usable(VkPhysicalDevice pd)
{
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    return p.apiVersion >= VK_API_VERSION_1_3 && find_queue_family(pd) >= 0;
}

#ifdef VKSKY_SANITIZE
/* LeakSanitizer reports at exit, after the loader has dlclosed the driver and the layer: their own leaks would show
 * as "<unknown module>" frames that no suppression can name. Keeping them mapped (RTLD_NODELETE) lets
 * tests/lsan.supp suppress them by library, so a leak of ours can never hide behind an unknown frame. */
static void keep_vulkan_libraries_mapped(void)
{
    const char *libs[] = {"libvulkan.so.1", "libvulkan_lvp.so", "libVkLayer_khronos_validation.so"};
    for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i)
        dlopen(libs[i], RTLD_LAZY | RTLD_NODELETE); /* absent ones (another driver) are fine */
}
#endif

/* The validation layer's messages to this context's callback (the messenger's user data is the context). */
static void attach_messenger(gpu_context *ctx)
{
    VkDebugUtilsMessengerCreateInfoEXT info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = debug_callback,
        .pUserData = ctx,
    };
    VK_CHECK(vkCreateDebugUtilsMessengerEXT(ctx->instance, &info, NULL, &ctx->messenger));
}

static int create_instance(gpu_context *ctx, const gpu_context_desc *desc, bool quiet)
{
#ifdef VKSKY_SANITIZE
    keep_vulkan_libraries_mapped();
#endif
    if (volkInitialize() != VK_SUCCESS) {
        if (!quiet) gpu_report(ctx, 2, "no Vulkan loader (libvulkan.so.1) found; install libvulkan1 and a driver (mesa-vulkan-drivers)");
        return -1;
    }
    if (volkGetInstanceVersion() < VK_API_VERSION_1_3) {
        if (!quiet) gpu_report(ctx, 2, "the Vulkan loader is older than 1.3");
        return -1;
    }
    const char *extensions[16];
    uint32_t ext_count = 0;
    for (unsigned i = 0; i < desc->instance_extension_count && ext_count < 14; ++i)
        extensions[ext_count++] = desc->instance_extensions[i];
    ctx->debug_utils = has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (ctx->debug_utils) extensions[ext_count++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    /* VK_EXT_swapchain_maintenance1's present fences need these on the instance (docs/synchronization.md §6). */
    ctx->surface_maintenance1 = desc->want_swapchain && ext_count <= 14 &&
                                has_instance_extension(VK_EXT_SURFACE_MAINTENANCE_1_EXTENSION_NAME) &&
                                has_instance_extension(VK_KHR_GET_SURFACE_CAPABILITIES_2_EXTENSION_NAME);
    if (ctx->surface_maintenance1) {
        extensions[ext_count++] = VK_KHR_GET_SURFACE_CAPABILITIES_2_EXTENSION_NAME;
        extensions[ext_count++] = VK_EXT_SURFACE_MAINTENANCE_1_EXTENSION_NAME;
    }

    const char *layers[1] = {"VK_LAYER_KHRONOS_validation"};
    if (desc->validation && !has_layer(layers[0])) {
        if (!quiet) gpu_report(ctx, 2, "--validate needs the Khronos validation layer (Debian package vulkan-validationlayers)");
        return -1;
    }
    if (desc->validation && !ctx->debug_utils) {
        if (!quiet) gpu_report(ctx, 2, "--validate needs VK_EXT_debug_utils, which this loader lacks");
        return -1;
    }
    /* Synchronization validation is off by default in the layer; it is the only thing that sees a missing
     * barrier on an in-order implementation like lavapipe. Chained on the instance, never on the messenger's
     * create info (VUID_Undefined pNext). */
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "vksky",
        .applicationVersion = VK_MAKE_VERSION(0, 1, 0),
        .pEngineName = "vksky",
        .apiVersion = VK_API_VERSION_1_3,
    };
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = desc->validation ? &features : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = desc->validation ? 1 : 0,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = ext_count,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult r = vkCreateInstance(&info, NULL, &ctx->instance);
    if (r != VK_SUCCESS) {
        if (!quiet) gpu_report(ctx, 2, "vkCreateInstance failed: %s", gpu_result_name(r));
        return -1;
    }
    volkLoadInstanceOnly(ctx->instance);
    ctx->validation = desc->validation;   /* its messages: attach_messenger, by the context that keeps it */
    return 0;
}

int gpu_list_devices(FILE *out)
{
    gpu_context ctx = {0};
    gpu_context_desc desc = {.device_index = -1};
    if (create_instance(&ctx, &desc, false) != 0) return -1;
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(ctx.instance, &n, NULL);
    VkPhysicalDevice pds[16];
    if (n > 16) n = 16;
    vkEnumeratePhysicalDevices(ctx.instance, &n, pds);
    for (uint32_t i = 0; i < n; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pds[i], &p);
        fprintf(out, "%u: %s (%s, Vulkan %u.%u.%u)%s\n", i, p.deviceName, device_type_name(p.deviceType),
                VK_API_VERSION_MAJOR(p.apiVersion), VK_API_VERSION_MINOR(p.apiVersion),
                VK_API_VERSION_PATCH(p.apiVersion), device_is_usable(pds[i]) ? "" : " [unusable: needs Vulkan 1.3]");
    }
    vkDestroyInstance(ctx.instance, NULL);
    return n ? 0 : -1;
}

/* Contexts created and not yet destroyed, and the device type of the last one (gpu_device_type). */
static int live_contexts;
static VkPhysicalDeviceType live_device_type;

/* quiet: no message (a probe; the context that follows reports what is wrong). */
static int pick_device(gpu_context *ctx, int index, bool quiet)
{
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(ctx->instance, &n, NULL);
    VkPhysicalDevice pds[16];
    if (n > 16) n = 16;
    vkEnumeratePhysicalDevices(ctx->instance, &n, pds);
    if (n == 0) {
        if (!quiet) gpu_report(ctx, 2, "no Vulkan device found; install a driver (mesa-vulkan-drivers provides lavapipe)");
        return -1;
    }
    if (index >= 0) {
        if ((uint32_t)index >= n) {
            if (!quiet) gpu_report(ctx, 2, "--device %d: there are %u devices (0..%u); see --list-devices", index, n, n - 1);
            return -2;
        }
        if (!device_is_usable(pds[index])) {
            if (!quiet) gpu_report(ctx, 2, "--device %d does not support Vulkan 1.3 with a graphics+compute queue", index);
            return -2;
        }
        ctx->physical = pds[index];
        return 0;
    }
    int best = -1, best_rank = -1;
    for (uint32_t i = 0; i < n; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pds[i], &p);
        if (device_is_usable(pds[i]) && device_rank(p.deviceType) > best_rank) {
            best = (int)i;
            best_rank = device_rank(p.deviceType);
        }
    }
    if (best < 0) {
        if (!quiet) gpu_report(ctx, 2, "no Vulkan 1.3 device with a graphics+compute queue");
        return -1;
    }
    ctx->physical = pds[best];
    return 0;
}

/* The probe's instance, kept for the context that usually follows (the device probed once, issue 27): an instance
 * without window extensions, with the validation layer when the run validates (gpu_device_type_for), is adopted by
 * gpu_context_create with the same validation; any other context destroys it first, and exit does if none came. */
static VkInstance parked;
static bool parked_debug_utils, parked_validation;

static void release_parked(void)
{
    if (parked) vkDestroyInstance(parked, NULL);
    parked = VK_NULL_HANDLE;
}

static void park(const gpu_context *probe)
{
    static bool registered;
    release_parked();
    parked = probe->instance, parked_debug_utils = probe->debug_utils, parked_validation = probe->validation;
    if (!registered) registered = atexit(release_parked) == 0;
    if (!registered) release_parked();
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* The probe's wall ms (--timings): its instance (volk's loader load included), then the enumeration; 0 if none ran. */
static double probe_instance_ms, probe_pick_ms;

void gpu_probe_times(double *instance_ms, double *enumerate_ms)
{
    *instance_ms = probe_instance_ms, *enumerate_ms = probe_pick_ms;
}

int gpu_device_type(int device_index, VkPhysicalDeviceType *type)
{
    return gpu_device_type_for(device_index, false, type);
}

int gpu_device_type_for(int device_index, bool validation, VkPhysicalDeviceType *type)
{
    /* With a context alive (the window re-reading its scene file), name its device: a second instance would
     * reload volk's instance functions, and destroying it would leave the live context calling into freed ones. */
    if (live_contexts > 0) {
        *type = live_device_type;
        return 0;
    }
    /* The devices do not change within a process: probe each index once (a sequence parses every frame's options,
     * and each parse of --quality auto asks). */
    static bool probed;
    static int probed_index, probed_result;
    static VkPhysicalDeviceType probed_type;
    if (probed && probed_index == device_index) {   /* the answer; its instance stays as it was parked */
        *type = probed_type;
        return probed_result;
    }
    gpu_context ctx = {0};
    gpu_context_desc desc = {.device_index = device_index, .validation = validation};
    double start = now_ms();
    /* Without the layer (or debug utils) a plain probe, quietly: the run's own context then says once what is
     * missing. */
    if (create_instance(&ctx, &desc, validation) != 0) {
        desc.validation = false;
        if (!validation || create_instance(&ctx, &desc, false) != 0) return -1;
    }
    double made = now_ms();
    int picked = pick_device(&ctx, device_index, true);
    probe_instance_ms = made - start, probe_pick_ms = now_ms() - made;
    if (picked == 0) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(ctx.physical, &p);
        *type = p.deviceType;
    }
    park(&ctx);
    probed = true, probed_index = device_index, probed_result = picked == 0 ? 0 : -1, probed_type = *type;
    return probed_result;
}

int gpu_context_create(gpu_context *ctx, const gpu_context_desc *desc)
{
    return gpu_context_create_with(ctx, desc, NULL, NULL, NULL);
}

/* --async-luts: the compute queue, a command pool on its family, the two timelines (gpu/async_queue.c uses them). */
static void open_compute_queue(gpu_context *ctx)
{
    vkGetDeviceQueue(ctx->device, ctx->compute_family, ctx->compute_index, &ctx->compute_queue);
    if (ctx->compute_queue != ctx->queue)
        gpu_set_name(ctx, VK_OBJECT_TYPE_QUEUE, (uint64_t)(uintptr_t)ctx->compute_queue, "async compute queue");
    VkCommandPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                     .queueFamilyIndex = ctx->compute_family};
    VK_CHECK(vkCreateCommandPool(ctx->device, &pinfo, ctx->allocator, &ctx->compute_pool));
    gpu_set_name(ctx, VK_OBJECT_TYPE_COMMAND_POOL, (uint64_t)ctx->compute_pool, "async compute command pool");
    ctx->compute_done = gpu_timeline_create(ctx->device, ctx->allocator);
    ctx->graphics_done = gpu_timeline_create(ctx->device, ctx->allocator);
    gpu_set_name(ctx, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)ctx->compute_done, "compute_done timeline");
    gpu_set_name(ctx, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)ctx->graphics_done, "graphics_done timeline");
}

int gpu_context_create_with(gpu_context *ctx, const gpu_context_desc *desc, gpu_message_fn message, void *user,
                            const VkAllocationCallbacks *allocator)
{
    *ctx = (gpu_context){.message = message, .message_user = user, .allocator = allocator, .owns_device = true};
    double start = now_ms();
    if (parked && parked_validation == desc->validation && desc->instance_extension_count == 0) {
        ctx->instance = parked, ctx->debug_utils = parked_debug_utils, ctx->instance_reused = true;
        ctx->validation = parked_validation;
        parked = VK_NULL_HANDLE;
    } else {
        release_parked();
        if (create_instance(ctx, desc, false) != 0) return -1;
    }
    if (desc->validation) attach_messenger(ctx);
    double instance_done = now_ms();
    int picked = pick_device(ctx, desc->device_index, false);
    if (picked != 0) {
        gpu_context_destroy(ctx);
        return picked;
    }
    vkGetPhysicalDeviceProperties(ctx->physical, &ctx->props);
    vkGetPhysicalDeviceMemoryProperties(ctx->physical, &ctx->memory);
    ctx->queue_family = (uint32_t)find_queue_family(ctx->physical);

    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical, &qn, NULL);
    VkQueueFamilyProperties qprops[16];
    if (qn > 16) qn = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical, &qn, qprops);
    ctx->timestamps = qprops[ctx->queue_family].timestampValidBits > 0 && ctx->props.limits.timestampPeriod > 0;
    ctx->timestamp_period_ns = ctx->props.limits.timestampPeriod;
    if (desc->async_compute && gpu_queue_choose_compute(qprops, qn, ctx->queue_family,
                                                         desc->async_compute == GPU_ASYNC_ONE_QUEUE,
                                                         &ctx->compute_family, &ctx->compute_index) != 0) {
        gpu_report(ctx, 2, "--async-luts needs a second queue: this device has no compute-only queue family and its "
                           "one graphics+compute family has %u queue; run without --async-luts",
                   qprops[ctx->queue_family].queueCount);
        gpu_context_destroy(ctx);
        return -2;   /* the option, refused for this device: the user's choice to change */
    }

    VkPhysicalDeviceSwapchainMaintenance1FeaturesEXT fsm1 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SWAPCHAIN_MAINTENANCE_1_FEATURES_EXT};
    bool want_sm1 = ctx->surface_maintenance1 &&
                    has_device_extension(ctx->physical, VK_EXT_SWAPCHAIN_MAINTENANCE_1_EXTENSION_NAME);
    VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                            .pNext = want_sm1 ? &fsm1 : NULL};
    VkPhysicalDeviceVulkan13Features f13 = {0};
    f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
    f13.pNext = &f12;
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f13};
    vkGetPhysicalDeviceFeatures2(ctx->physical, &f2);
    if (!f13.synchronization2 || !f13.dynamicRendering || !f13.maintenance4) {
        gpu_report(ctx, 2, "the device lacks synchronization2, dynamicRendering or maintenance4");
        gpu_context_destroy(ctx);
        return -1;
    }
    /* Present fences where the device has them (the window's semaphore lifetime, docs/synchronization.md §6). */
    ctx->present_fences = want_sm1 && fsm1.swapchainMaintenance1;
    VkPhysicalDeviceSwapchainMaintenance1FeaturesEXT enable_sm1 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SWAPCHAIN_MAINTENANCE_1_FEATURES_EXT,
        .swapchainMaintenance1 = VK_TRUE};
    /* The Vulkan memory model and its device scope where the device has them (bloom_spd.comp; §7 of the guide). */
    VkPhysicalDeviceVulkan12Features enable12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = ctx->present_fences ? &enable_sm1 : NULL,
        .vulkanMemoryModel = f12.vulkanMemoryModel,
        .vulkanMemoryModelDeviceScope = f12.vulkanMemoryModelDeviceScope,
        .timelineSemaphore = desc->async_compute ? VK_TRUE : VK_FALSE,   /* core 1.2, required by 1.3 */
    };
    ctx->memory_model_device_scope = f12.vulkanMemoryModel && f12.vulkanMemoryModelDeviceScope;
    /* maintenance4: glslang 12 emits LocalSizeId for vulkan1.3 targets. */
    VkPhysicalDeviceVulkan13Features enable13 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
        .pNext = &enable12,
        .synchronization2 = VK_TRUE,
        .dynamicRendering = VK_TRUE,
        .maintenance4 = VK_TRUE,
    };
    float priority[2] = {1.0f, 1.0f};
    VkDeviceQueueCreateInfo qinfo[2] = {{
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = ctx->queue_family,
        .queueCount = 1,
        .pQueuePriorities = priority,
    }};
    uint32_t qinfo_count = desc->async_compute ? gpu_queue_infos(ctx->queue_family, ctx->compute_family,
                                                                 ctx->compute_index, qinfo, priority)
                                                 : 1;
    const char *dev_ext[2] = {VK_KHR_SWAPCHAIN_EXTENSION_NAME, VK_EXT_SWAPCHAIN_MAINTENANCE_1_EXTENSION_NAME};
    VkDeviceCreateInfo dinfo = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &enable13,
        .queueCreateInfoCount = qinfo_count,
        .pQueueCreateInfos = qinfo,
        .enabledExtensionCount = desc->want_swapchain ? (ctx->present_fences ? 2 : 1) : 0,
        .ppEnabledExtensionNames = dev_ext,
    };
    VkResult r = vkCreateDevice(ctx->physical, &dinfo, ctx->allocator, &ctx->device);
    if (r != VK_SUCCESS) {
        gpu_report(ctx, 2, "vkCreateDevice failed: %s", gpu_result_name(r));
        gpu_context_destroy(ctx);
        return -1;
    }
    /* Device functions straight from the driver while this is the only context of the process; beside another
     * (an adopted host device may run on another driver) through the loader's dispatch, right for every device. */
    if (gpu_context_live_count() == 0) volkLoadDevice(ctx->device);
    else volkLoadInstance(ctx->instance);
    gpu_allocator_register(ctx->device, ctx->allocator);
    vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);
    gpu_set_name(ctx, VK_OBJECT_TYPE_QUEUE, (uint64_t)(uintptr_t)ctx->queue, "main queue");

    VkCommandPoolCreateInfo pinfo = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = ctx->queue_family,
    };
    VK_CHECK(vkCreateCommandPool(ctx->device, &pinfo, ctx->allocator, &ctx->command_pool));
    gpu_set_name(ctx, VK_OBJECT_TYPE_COMMAND_POOL, (uint64_t)ctx->command_pool, "main command pool");
    if (desc->async_compute) open_compute_queue(ctx);
    live_contexts++;
    gpu_context_live_add(1);
    live_device_type = ctx->props.deviceType;
    ctx->instance_ms = instance_done - start;
    ctx->device_ms = now_ms() - instance_done;
    return 0;
}

void gpu_context_destroy(gpu_context *ctx)
{
    /* A cache directory still attached (gpu_cache_dir_attach without a detach or gpu_pipeline_cache_close, as the
     * test harness's shared LUT cache): its record (pipeline_cache.c's, a plain allocation) goes with the context. */
    free(ctx->cache_file);
    ctx->cache_file = NULL;
    if (!ctx->owns_device) {
        gpu_context_release(ctx);   /* the host's device: only what vksky made on it (context_adopt.c) */
        return;
    }
    if (ctx->command_pool && live_contexts > 0) live_contexts--, gpu_context_live_add(-1);   /* counted once created */
    if (ctx->device) {
        vkDeviceWaitIdle(ctx->device);
        if (ctx->compute_pool) {   /* --async-luts */
            vkDestroySemaphore(ctx->device, ctx->compute_done, ctx->allocator);
            vkDestroySemaphore(ctx->device, ctx->graphics_done, ctx->allocator);
            vkDestroyCommandPool(ctx->device, ctx->compute_pool, ctx->allocator);
        }
        if (ctx->command_pool) vkDestroyCommandPool(ctx->device, ctx->command_pool, ctx->allocator);
        gpu_allocator_register(ctx->device, NULL);
        vkDestroyDevice(ctx->device, ctx->allocator);
    }
    if (ctx->messenger) vkDestroyDebugUtilsMessengerEXT(ctx->instance, ctx->messenger, NULL);
    if (ctx->instance) vkDestroyInstance(ctx->instance, NULL);
    *ctx = (gpu_context){0};
}

VkCommandBuffer gpu_begin_commands(const gpu_context *ctx)
{
    gpu_barrier_trace_commands();
    VkCommandBufferAllocateInfo ainfo = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = ctx->command_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer cmd;
    VK_CHECK(vkAllocateCommandBuffers(ctx->device, &ainfo, &cmd));
    VkCommandBufferBeginInfo binfo = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VK_CHECK(vkBeginCommandBuffer(cmd, &binfo));
    return cmd;
}

void gpu_submit_and_wait(const gpu_context *ctx, VkCommandBuffer cmd)
{
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    VK_CHECK(vkCreateFence(ctx->device, &finfo, ctx->allocator, &fence));
    VkCommandBufferSubmitInfo cinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 sinfo = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
        .commandBufferInfoCount = 1,
        .pCommandBufferInfos = &cinfo,
    };
    VK_CHECK(vkQueueSubmit2(ctx->queue, 1, &sinfo, fence));
    VK_CHECK(vkWaitForFences(ctx->device, 1, &fence, VK_TRUE, UINT64_MAX));
    vkDestroyFence(ctx->device, fence, ctx->allocator);
    vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &cmd);
}
