/* Interactive window: GLFW + a Vulkan swapchain, two frames in flight, the fly camera and the lesson's controls.
 *
 * Presentation in one paragraph. Each frame slot (FRAMES_IN_FLIGHT = 2) owns a fence, an "image acquired"
 * semaphore, a command buffer and a timestamp pool; waiting on the slot's fence makes all four reusable. Each
 * swapchain IMAGE owns a "render finished" semaphore: the presentation engine waits on it at some unknown time
 * after vkQueuePresentKHR, and the only moment we know that wait is over is when the same image is acquired
 * again, so the semaphore must follow the image, not the frame slot. The submit waits on the acquire semaphore
 * at COLOR_ATTACHMENT_OUTPUT: the LUT, sky and bloom passes do not touch the swapchain image and may run before
 * the presentation engine lets go of it; the spine's first barrier on the image (usage GPU_USAGE_ACQUIRED)
 * starts from that same stage, so its layout transition is chained after the wait. The spine ends with the
 * barrier to PRESENT_SRC, and the submit signals the image's semaphore at ALL_COMMANDS so that the tone map's
 * writes, the optional screenshot copy and that layout transition all happen before presentation.
 *
 * Swapchain life: recreated (with oldSwapchain) when the framebuffer size changes, or acquire/present say
 * OUT_OF_DATE or SUBOPTIMAL; no frame is drawn while the window is minimised (we sleep in glfwWaitEvents). */
#include <volk.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/camera.h"
#include "app/window.h"
#include "io/image_io.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FRAMES_IN_FLIGHT 2
#define MAX_IMAGES 8
#define SUN_RATE_DEG_S 30.0
#define AUTO_SUN_RATE_DEG_S 15.0
#define LOOK_DEG_PER_PIXEL 0.1
#define TITLE_PERIOD_S 0.5

static const char NO_DISPLAY[] = "vksky: no display available (DISPLAY/WAYLAND_DISPLAY unset or unusable); use "
                                 "--render FILE.exr|FILE.png for headless rendering";

typedef struct swapchain {
    VkSwapchainKHR handle;
    VkSurfaceFormatKHR format;
    VkExtent2D extent;
    uint32_t count;
    VkImage images[MAX_IMAGES];
    VkImageView views[MAX_IMAGES];
    VkSemaphore render_finished[MAX_IMAGES];   /* per image: see the top of the file */
    bool can_copy;                             /* TRANSFER_SRC usage: screenshots */
} swapchain;

typedef struct frame_slot {
    VkCommandBuffer cmd;
    VkFence done;              /* signalled when this slot's last submission finished */
    VkSemaphore acquired;
    gpu_timer timer;
    bool timer_unread;         /* submitted; its timestamps are not yet read */
} frame_slot;

typedef struct input_state {
    bool captured;             /* cursor disabled: mouse look */
    bool have_cursor;
    double cursor_x, cursor_y;
    double look_dx, look_dy;   /* pixels since the last frame */
    bool auto_sun;
} input_state;

typedef struct stats {
    double start, title_time, last_frame;
    long title_frames;
    double gpu_ms_sum, gpu_ms_total;
    long gpu_samples, gpu_samples_total;
} stats;

typedef struct test_hooks {
    bool resize;               /* VKSKY_TEST_RESIZE=1: resize 3 times, minimise and restore once */
    long last_frame;           /* the presented count the hook last acted on */
    int minimized_waits;       /* > 0: we minimised the window; restore after a few idle waits */
    bool hid;                  /* no window manager iconified it: we unmapped it ourselves */
} test_hooks;

typedef struct app {
    const options *o;
    GLFWwindow *window;
    gpu_context ctx;
    VkSurfaceKHR surface;
    swapchain sc;
    frame_slot frames[FRAMES_IN_FLIGHT];
    uint32_t slot;
    sky_renderer renderer;
    sky_view view;
    camera cam;
    input_state in;
    stats st;
    test_hooks test;
    bool swapchain_dirty;      /* resize seen, or acquire/present reported OUT_OF_DATE / SUBOPTIMAL */
    long presented;
    bool traced;
    int status;
} app;

/* --- GLFW errors: kept, not printed (no-display runs must print exactly one line) ------------------------- */

static char glfw_error[256];

static void on_glfw_error(int code, const char *text)
{
    snprintf(glfw_error, sizeof glfw_error, "GLFW error 0x%x: %s", code, text ? text : "");
}

/* --- Controls ---------------------------------------------------------------------------------------------- */

static void print_controls(void)
{
    printf("vksky controls\n"
           "  W A S D        fly forward / left / back / right (0.2 km/s)\n"
           "  Space / C      fly up / down (along the local vertical)\n"
           "  Left Shift     10x speed\n"
           "  mouse          look around (click the window to capture the cursor)\n"
           "  Left / Right   sun azimuth (30 deg/s)\n"
           "  Up / Down      sun elevation (30 deg/s, -90..90)\n"
           "  T              automatic sun rotation (azimuth, 15 deg/s) on/off\n"
           "  1 / 2 / 3      tone map: clamp / Reinhard / ACES\n"
           "  = + / -        exposure +/- 0.5 EV\n"
           "  B              bloom on/off\n"
           "  Escape         release the mouse; again: quit\n"
           "  F5             reload the --scene file (recomputes only what changed)\n"
           "  F1 / H         this table\n");
    fflush(stdout);
}

static void set_captured(app *a, bool captured)
{
    a->in.captured = captured;
    a->in.have_cursor = false;   /* the first motion after a mode change is a jump, not a look */
    glfwSetInputMode(a->window, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
    if (glfwRawMouseMotionSupported())
        glfwSetInputMode(a->window, GLFW_RAW_MOUSE_MOTION, captured ? GLFW_TRUE : GLFW_FALSE);
}

static const char *tonemap_name(int t)
{
    return t == VKSKY_TONEMAP_CLAMP ? "clamp" : t == VKSKY_TONEMAP_REINHARD ? "reinhard" : "aces";
}

/* Discrete keys (toggles, steps) act on the press; held keys are polled once a frame in read_input. */
/* F5: reload the scene file's medium and features. The renderer recomputes only what changed: the LUTs when
 * their inputs' hash changed, the pipelines when the variant changed. The camera and the sun stay where the user
 * put them. A broken file leaves the current scene (its one-line error is printed). */
static void reload_scene(app *a)
{
    if (!a->o->scene_path) {
        printf("F5: no --scene file to reload\n");
        return;
    }
    char *argv[] = {"vksky", "--scene", (char *)a->o->scene_path, "--render", "x.png"};
    options fresh;
    if (options_parse(&fresh, 5, argv) != 0) return;
    /* The atmosphere uniform buffer is shared by the frames in flight: wait for them before rewriting it. */
    vkDeviceWaitIdle(a->ctx.device);
    sky_variant before = a->renderer.variant;
    sky_renderer_set_atmosphere(&a->renderer, &fresh.atmosphere, options_sun_radius_rad(&fresh));
    sky_features features = options_features(&fresh);
    sky_renderer_set_features(&a->renderer, &features);
    printf("scene reloaded: %s (LUTs %s, pipelines %s)\n", a->o->scene_path,
           sky_renderer_luts_dirty(&a->renderer) ? "recomputed" : "kept",
           memcmp(&before, &a->renderer.variant, sizeof before) ? "rebuilt" : "kept");
    fflush(stdout);
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    if (action != GLFW_PRESS) return;
    app *a = glfwGetWindowUserPointer(w);
    sky_view *v = &a->view;
    switch (key) {
    case GLFW_KEY_ESCAPE:
        if (a->in.captured) set_captured(a, false);
        else glfwSetWindowShouldClose(w, GLFW_TRUE);
        return;
    case GLFW_KEY_T: a->in.auto_sun = !a->in.auto_sun; printf("auto sun %s\n", a->in.auto_sun ? "on" : "off"); break;
    case GLFW_KEY_1: v->tonemap = VKSKY_TONEMAP_CLAMP; break;
    case GLFW_KEY_2: v->tonemap = VKSKY_TONEMAP_REINHARD; break;
    case GLFW_KEY_3: v->tonemap = VKSKY_TONEMAP_ACES; break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: v->exposure_ev = fmin(20.0, v->exposure_ev + 0.5); break;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: v->exposure_ev = fmax(-20.0, v->exposure_ev - 0.5); break;
    case GLFW_KEY_B: v->bloom = !v->bloom; printf("bloom %s\n", v->bloom ? "on" : "off"); break;
    case GLFW_KEY_F1: case GLFW_KEY_H: print_controls(); return;
    case GLFW_KEY_F5: reload_scene(a); return;
    default: return;
    }
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_3) printf("tonemap %s\n", tonemap_name(v->tonemap));
    if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD || key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT)
        printf("exposure %+.1f EV\n", v->exposure_ev);
    fflush(stdout);
}

static void on_mouse_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    app *a = glfwGetWindowUserPointer(w);
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS && !a->in.captured) set_captured(a, true);
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    app *a = glfwGetWindowUserPointer(w);
    if (a->in.captured && a->in.have_cursor) {
        a->in.look_dx += x - a->in.cursor_x;
        a->in.look_dy += y - a->in.cursor_y;
    }
    a->in.cursor_x = x, a->in.cursor_y = y, a->in.have_cursor = true;
}

static void on_framebuffer_size(GLFWwindow *w, int width, int height)
{
    (void)width, (void)height;
    app *a = glfwGetWindowUserPointer(w);
    a->swapchain_dirty = true;
}

static double key_axis(GLFWwindow *w, int positive, int negative)
{
    return (glfwGetKey(w, positive) == GLFW_PRESS ? 1.0 : 0.0) - (glfwGetKey(w, negative) == GLFW_PRESS ? 1.0 : 0.0);
}

/* Held keys and the mouse since the last frame -> camera and sun, over dt seconds of wall time. */
static void read_input(app *a, double dt)
{
    GLFWwindow *w = a->window;
    camera_input in = {
        .forward = key_axis(w, GLFW_KEY_W, GLFW_KEY_S),
        .right = key_axis(w, GLFW_KEY_D, GLFW_KEY_A),
        .up = key_axis(w, GLFW_KEY_SPACE, GLFW_KEY_C),
        .boost = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS,
        .yaw_deg = a->in.look_dx * LOOK_DEG_PER_PIXEL,
        .pitch_deg = -a->in.look_dy * LOOK_DEG_PER_PIXEL,   /* screen y grows downwards */
        .sun_azimuth_deg = (key_axis(w, GLFW_KEY_RIGHT, GLFW_KEY_LEFT) * SUN_RATE_DEG_S +
                            (a->in.auto_sun ? AUTO_SUN_RATE_DEG_S : 0.0)) * dt,
        .sun_elevation_deg = key_axis(w, GLFW_KEY_UP, GLFW_KEY_DOWN) * SUN_RATE_DEG_S * dt,
    };
    a->in.look_dx = a->in.look_dy = 0.0;
    camera_update(&a->cam, &in, dt);
    camera_to_view(&a->cam, &a->view);
}

/* --- Swapchain --------------------------------------------------------------------------------------------- */

/* An 8-bit sRGB format lets the hardware encode; a UNORM one makes the spine tell the tone map to encode sRGB
 * itself (frame.c checks the format). Anything else: the surface's first format. */
static VkSurfaceFormatKHR choose_format(const app *a)
{
    VkSurfaceFormatKHR formats[64];
    uint32_t n = 64;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(a->ctx.physical, a->surface, &n, formats));
    static const VkFormat preferred[] = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM,
                                         VK_FORMAT_R8G8B8A8_UNORM};
    for (size_t p = 0; p < sizeof preferred / sizeof preferred[0]; ++p)
        for (uint32_t i = 0; i < n; ++i)
            if (formats[i].format == preferred[p] && formats[i].colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
                return formats[i];
    return formats[0];
}

static void swapchain_destroy_views(app *a, swapchain *sc)
{
    for (uint32_t i = 0; i < sc->count; ++i) {
        vkDestroyImageView(a->ctx.device, sc->views[i], NULL);
        vkDestroySemaphore(a->ctx.device, sc->render_finished[i], NULL);
    }
    sc->count = 0;
}

static VkExtent2D swapchain_extent(const app *a, const VkSurfaceCapabilitiesKHR *caps)
{
    if (caps->currentExtent.width != UINT32_MAX) return caps->currentExtent;
    int w, h;
    glfwGetFramebufferSize(a->window, &w, &h);
    VkExtent2D e = {(uint32_t)w, (uint32_t)h};
    e.width = e.width < caps->minImageExtent.width ? caps->minImageExtent.width : e.width;
    e.width = e.width > caps->maxImageExtent.width ? caps->maxImageExtent.width : e.width;
    e.height = e.height < caps->minImageExtent.height ? caps->minImageExtent.height : e.height;
    e.height = e.height > caps->maxImageExtent.height ? caps->maxImageExtent.height : e.height;
    return e;
}

static void swapchain_create_views(app *a, swapchain *sc)
{
    const gpu_context *ctx = &a->ctx;
    sc->count = MAX_IMAGES;
    VK_CHECK(vkGetSwapchainImagesKHR(ctx->device, sc->handle, &sc->count, sc->images));
    VkSemaphoreCreateInfo sinfo = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (uint32_t i = 0; i < sc->count; ++i) {
        VkImageViewCreateInfo vinfo = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = sc->images[i],
                                       .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = sc->format.format,
                                       .subresourceRange = gpu_color_range(0, 1)};
        VK_CHECK(vkCreateImageView(ctx->device, &vinfo, NULL, &sc->views[i]));
        VK_CHECK(vkCreateSemaphore(ctx->device, &sinfo, NULL, &sc->render_finished[i]));
        char name[48];
        snprintf(name, sizeof name, "swapchain image %u", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE, (uint64_t)sc->images[i], name);
        gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)sc->views[i], name);
        snprintf(name, sizeof name, "render finished %u", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)sc->render_finished[i], name);
    }
}

/* (Re)create the swapchain at the surface's current size. Returns false while the surface has no area
 * (minimised). The caller has waited for the device to go idle: nothing still uses the old images, their
 * views or semaphores (a present's semaphore wait is a queue operation, finished once the queue is idle). */
static bool swapchain_create(app *a)
{
    const gpu_context *ctx = &a->ctx;
    swapchain *sc = &a->sc;
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx->physical, a->surface, &caps));
    VkExtent2D extent = swapchain_extent(a, &caps);
    if (extent.width == 0 || extent.height == 0) return false;
    uint32_t count = caps.minImageCount + 1;   /* one spare: acquire need not wait for the oldest present */
    if (caps.maxImageCount && count > caps.maxImageCount) count = caps.maxImageCount;
    if (count > MAX_IMAGES) count = MAX_IMAGES;
    sc->can_copy = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    VkSwapchainKHR old = sc->handle;
    VkSwapchainCreateInfoKHR info = {
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR, .surface = a->surface, .minImageCount = count,
        .imageFormat = sc->format.format, .imageColorSpace = sc->format.colorSpace, .imageExtent = extent,
        .imageArrayLayers = 1,
        .imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (sc->can_copy ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0),
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE, .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, .presentMode = VK_PRESENT_MODE_FIFO_KHR,  /* always there */
        .clipped = VK_TRUE, .oldSwapchain = old,
    };
    if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR))
        info.compositeAlpha = VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
    VK_CHECK(vkCreateSwapchainKHR(ctx->device, &info, NULL, &sc->handle));
    swapchain_destroy_views(a, sc);
    if (old) vkDestroySwapchainKHR(ctx->device, old, NULL);
    sc->extent = extent;
    swapchain_create_views(a, sc);
    gpu_set_name(ctx, VK_OBJECT_TYPE_SWAPCHAIN_KHR, (uint64_t)sc->handle, "swapchain");
    if (a->test.resize) printf("swapchain %ux%u images %u\n", extent.width, extent.height, sc->count);
    return true;
}

/* Resize, OUT_OF_DATE or SUBOPTIMAL: a new swapchain and a renderer of the new size. Waiting for the device
 * first keeps it simple: nothing in flight still uses the old swapchain or the old-size render targets. */
static void swapchain_recreate(app *a)
{
    VK_CHECK(vkDeviceWaitIdle(a->ctx.device));
    if (!swapchain_create(a)) {
        /* The surface has no area yet (minimised, or the resize still on its way): stay dirty, don't spin. */
        glfwWaitEventsTimeout(0.05);
        return;
    }
    sky_renderer_resize(&a->renderer, a->sc.extent.width, a->sc.extent.height);
    a->swapchain_dirty = false;
}

/* --- Frames in flight -------------------------------------------------------------------------------------- */

static void frames_create(app *a)
{
    const gpu_context *ctx = &a->ctx;
    VkCommandBufferAllocateInfo ainfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                         .commandPool = ctx->command_pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                         .commandBufferCount = 1};
    /* Signalled at creation: the first wait on each slot returns at once. */
    VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
    VkSemaphoreCreateInfo sinfo = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (int i = 0; i < FRAMES_IN_FLIGHT; ++i) {
        frame_slot *f = &a->frames[i];
        VK_CHECK(vkAllocateCommandBuffers(ctx->device, &ainfo, &f->cmd));
        VK_CHECK(vkCreateFence(ctx->device, &finfo, NULL, &f->done));
        VK_CHECK(vkCreateSemaphore(ctx->device, &sinfo, NULL, &f->acquired));
        gpu_timer_create(ctx, &f->timer);
        char name[48];
        snprintf(name, sizeof name, "frame %d commands", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_COMMAND_BUFFER, (uint64_t)(uintptr_t)f->cmd, name);
        snprintf(name, sizeof name, "frame %d done", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_FENCE, (uint64_t)f->done, name);
        snprintf(name, sizeof name, "frame %d image acquired", i);
        gpu_set_name(ctx, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)f->acquired, name);
    }
}

static void frames_destroy(app *a)
{
    for (int i = 0; i < FRAMES_IN_FLIGHT; ++i) {
        frame_slot *f = &a->frames[i];
        vkDestroyFence(a->ctx.device, f->done, NULL);
        vkDestroySemaphore(a->ctx.device, f->acquired, NULL);
        gpu_timer_destroy(&a->ctx, &f->timer);
        vkFreeCommandBuffers(a->ctx.device, a->ctx.command_pool, 1, &f->cmd);
    }
}

/* After the slot's fence: its timestamps are final. The frame's GPU time is the sum of its passes. */
static void read_timer(app *a, frame_slot *f)
{
    if (!f->timer_unread) return;
    f->timer_unread = false;
    double ms[GPU_TIMER_MAX], sum = 0.0;
    uint32_t n = gpu_timer_read(&a->ctx, &f->timer, ms);
    for (uint32_t i = 0; i < n; ++i) sum += ms[i];
    if (n == 0) return;
    a->st.gpu_ms_sum += sum, a->st.gpu_samples++;
    a->st.gpu_ms_total += sum, a->st.gpu_samples_total++;
}

/* Record the frame into the slot's command buffer: the spine does all of it, ending on the PRESENT barrier. */
static void record(app *a, frame_slot *f, uint32_t image, gpu_buffer *capture)
{
    VK_CHECK(vkResetCommandBuffer(f->cmd, 0));
    VkCommandBufferBeginInfo binfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(f->cmd, &binfo));
    frame_target target = {a->sc.images[image], a->sc.views[image], a->sc.extent, GPU_USAGE_ACQUIRED,
                           GPU_USAGE_PRESENT, capture};
    /* The renderer's own images (HDR, bloom mips, LUTs) are shared by both frames in flight. That is safe
     * without per-frame copies: both frames go to one queue, and a pipeline barrier's source scope covers
     * every command submitted before it on that queue, earlier submissions included. So the spine's first
     * barrier on the HDR image in frame N+1 (WAR against the "fragment sampled" reads) waits for frame N's
     * bloom and tone map reads, even though frame N was a different vkQueueSubmit2. Frames in flight overlap
     * CPU recording with GPU work; on the GPU they run one after the other. */
    if (a->o->trace_barriers && !a->traced) gpu_barrier_trace(stdout);
    frame_record(&a->renderer, f->cmd, &(frame_desc){.view = &a->view, .target = &target, .timer = &f->timer});
    if (a->o->trace_barriers && !a->traced) gpu_barrier_trace(NULL), a->traced = true;
    VK_CHECK(vkEndCommandBuffer(f->cmd));
}

static void submit(app *a, frame_slot *f, uint32_t image)
{
    /* Wait for the image where it is first written (see the top of the file); signal once everything in the
     * command buffer, the final layout transition included, is done. */
    VkSemaphoreSubmitInfo wait = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = f->acquired,
                                  .stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT};
    VkSemaphoreSubmitInfo signal = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                    .semaphore = a->sc.render_finished[image],
                                    .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo cmd = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = f->cmd};
    VkSubmitInfo2 info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = 1,
                          .pWaitSemaphoreInfos = &wait, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cmd,
                          .signalSemaphoreInfoCount = 1, .pSignalSemaphoreInfos = &signal};
    /* Reset only now that a submit follows for sure: a reset fence nobody signals would hang the next wait. */
    VK_CHECK(vkResetFences(a->ctx.device, 1, &f->done));
    VK_CHECK(vkQueueSubmit2(a->ctx.queue, 1, &info, f->done));
    f->timer_unread = true;
}

static void present(app *a, uint32_t image)
{
    VkPresentInfoKHR info = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, .waitSemaphoreCount = 1,
                             .pWaitSemaphores = &a->sc.render_finished[image], .swapchainCount = 1,
                             .pSwapchains = &a->sc.handle, .pImageIndices = &image};
    VkResult r = vkQueuePresentKHR(a->ctx.queue, &info);
    /* Even when rejected as OUT_OF_DATE the present's semaphore wait still executes; recreate next loop. */
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) a->swapchain_dirty = true;
    else VK_CHECK(r);
}

/* One frame: wait for the slot, acquire, record, submit, present. Returns false when nothing was submitted
 * (acquire said OUT_OF_DATE: no image, no semaphore signal, the fence left signalled for the retry). */
static bool draw_frame(app *a, gpu_buffer *capture)
{
    frame_slot *f = &a->frames[a->slot];
    /* The slot's previous submission is done: its command buffer, semaphore and timestamps are free. */
    VK_CHECK(vkWaitForFences(a->ctx.device, 1, &f->done, VK_TRUE, UINT64_MAX));
    read_timer(a, f);
    uint32_t image = 0;
    VkResult r = vkAcquireNextImageKHR(a->ctx.device, a->sc.handle, UINT64_MAX, f->acquired, VK_NULL_HANDLE, &image);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        a->swapchain_dirty = true;
        return false;
    }
    /* SUBOPTIMAL still acquired the image and will signal the semaphore: draw and present it, then recreate. */
    if (r == VK_SUBOPTIMAL_KHR) a->swapchain_dirty = true;
    else VK_CHECK(r);
    record(a, f, image, capture);
    submit(a, f, image);
    present(a, image);
    a->slot = (a->slot + 1) % FRAMES_IN_FLIGHT;
    a->presented++;
    return true;
}

/* --- Screenshot -------------------------------------------------------------------------------------------- */

static bool format_is_bgra(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM; }

static bool format_is_rgba8(VkFormat f)
{
    return format_is_bgra(f) || f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_R8G8B8A8_UNORM ||
           f == VK_FORMAT_A8B8G8R8_SRGB_PACK32 || f == VK_FORMAT_A8B8G8R8_UNORM_PACK32;
}

/* The last frame again, with the spine copying the swapchain image into a host buffer; after its fence the
 * pixels are written as PNG. Both sRGB and UNORM swapchains hold sRGB-encoded bytes (the tone map encodes for
 * UNORM), so the PNG is tagged sRGB either way. Returns false if the frame could not be drawn yet. */
static bool draw_screenshot_frame(app *a)
{
    VkExtent2D e = a->sc.extent;
    gpu_buffer buf;
    gpu_buffer_create(&a->ctx, &buf, "screenshot", (VkDeviceSize)e.width * e.height * 4,
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    frame_slot *f = &a->frames[a->slot];
    if (!draw_frame(a, &buf)) {
        gpu_buffer_destroy(&a->ctx, &buf);
        return false;
    }
    VK_CHECK(vkWaitForFences(a->ctx.device, 1, &f->done, VK_TRUE, UINT64_MAX));
    gpu_buffer_invalidate(&a->ctx, &buf);
    uint8_t *px = buf.mapped;
    if (format_is_bgra(a->sc.format.format))
        for (size_t i = 0; i < (size_t)e.width * e.height; ++i) {
            uint8_t t = px[4 * i];
            px[4 * i] = px[4 * i + 2], px[4 * i + 2] = t;
        }
    char err[512];
    if (io_write_png(a->o->screenshot, (int)e.width, (int)e.height, px, 1, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --screenshot: %s\n", err);
        a->status = 1;
    }
    gpu_buffer_destroy(&a->ctx, &buf);
    return true;
}

/* --- Title, test hooks, the loop --------------------------------------------------------------------------- */

static void update_title(app *a, double now)
{
    a->st.title_frames++;
    double elapsed = now - a->st.title_time;
    if (elapsed < TITLE_PERIOD_S) return;
    double fps = (double)a->st.title_frames / elapsed;
    double gpu = a->st.gpu_samples ? a->st.gpu_ms_sum / (double)a->st.gpu_samples : 0.0;
    double h = a->view.altitude_km;
    char title[160];
    snprintf(title, sizeof title, "vksky | %.1f fps | GPU %.2f ms | sun %.1f\xc2\xb0 | altitude %.*f %s", fps, gpu,
             a->view.sun_elevation_deg, h < 1.0 ? 1 : 3, h < 1.0 ? h * 1000.0 : h, h < 1.0 ? "m" : "km");
    glfwSetWindowTitle(a->window, title);
    a->st.title_time = now, a->st.title_frames = 0, a->st.gpu_ms_sum = 0.0, a->st.gpu_samples = 0;
}

/* VKSKY_TEST_RESIZE=1: resize at presented frames 20, 40, 60 and minimise at 80 (driven from inside: reliable
 * under Xvfb with no window manager). Without a window manager nobody honours an iconify request, so we then
 * unmap the window ourselves, which is what a window manager does to an iconified window on X11. */
static void test_hook(app *a)
{
    static const int sizes[3][2] = {{400, 240}, {256, 144}, {480, 270}};
    if (!a->test.resize || a->presented == a->test.last_frame) return;
    a->test.last_frame = a->presented;
    if (a->presented == 20 || a->presented == 40 || a->presented == 60) {
        int k = (int)(a->presented / 20) - 1;
        glfwSetWindowSize(a->window, sizes[k][0], sizes[k][1]);
    } else if (a->presented == 80) {
        glfwIconifyWindow(a->window);
        glfwWaitEventsTimeout(0.2);
        a->test.hid = !glfwGetWindowAttrib(a->window, GLFW_ICONIFIED);
        if (a->test.hid) glfwHideWindow(a->window);
        a->test.minimized_waits = 1;
    }
}

/* Nothing to present to: an iconified or unmapped window, or a 0x0 framebuffer (minimised on some platforms). */
static bool window_minimized(app *a)
{
    int w, h;
    glfwGetFramebufferSize(a->window, &w, &h);
    return w == 0 || h == 0 || glfwGetWindowAttrib(a->window, GLFW_ICONIFIED) ||
           !glfwGetWindowAttrib(a->window, GLFW_VISIBLE);
}

/* Sleep in the event queue until the window is back (no spinning). The test hook restores it itself. */
static void wait_while_minimized(app *a)
{
    while (!glfwWindowShouldClose(a->window) && window_minimized(a)) {
        if (!a->test.minimized_waits) {
            glfwWaitEvents();
            continue;
        }
        glfwWaitEventsTimeout(0.05);
        if (++a->test.minimized_waits <= 10) continue;
        printf("test: minimized for %d event waits (%s), restoring\n", a->test.minimized_waits - 1,
               a->test.hid ? "unmapped" : "iconified");
        a->test.minimized_waits = 0;
        if (a->test.hid) glfwShowWindow(a->window);
        else glfwRestoreWindow(a->window);
    }
    a->st.last_frame = glfwGetTime();   /* the time asleep is not camera movement */
}

static void run_loop(app *a)
{
    const options *o = a->o;
    bool quitting = false;
    for (;;) {
        glfwPollEvents();
        quitting = quitting || glfwWindowShouldClose(a->window) || (o->frames && a->presented >= o->frames);
        /* Closing with --screenshot: one last frame carries the capture, so it is the image on screen. */
        if (quitting && !o->screenshot) break;
        if (window_minimized(a)) {
            if (quitting) {
                if (o->screenshot) {
                    fprintf(stderr, "vksky: --screenshot: the window was minimised when it closed; no screenshot\n");
                    a->status = 1;
                }
                break;
            }
            wait_while_minimized(a);
            continue;
        }
        if (a->swapchain_dirty) {
            swapchain_recreate(a);
            continue;
        }
        double now = glfwGetTime(), dt = fmin(1.0, now - a->st.last_frame);
        a->st.last_frame = now;
        read_input(a, dt);
        bool last = quitting || (o->frames && a->presented + 1 == o->frames);
        if (last && o->screenshot) {
            if (draw_screenshot_frame(a)) break;
            continue;
        }
        if (draw_frame(a, NULL)) update_title(a, now);
        test_hook(a);
    }
}

/* --- Setup and teardown ------------------------------------------------------------------------------------ */

/* No X server / compositor (or one that refuses us): one line, exit 2, like any other unusable input. */
static int no_display(void)
{
    fprintf(stderr, "%s\n", NO_DISPLAY);
    return 2;
}

static int open_window(app *a)
{
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) return no_display();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    a->window = glfwCreateWindow(a->o->width, a->o->height, "vksky", NULL, NULL);
    if (!a->window) return no_display();
    if (!glfwVulkanSupported()) {
        fprintf(stderr, "vksky: GLFW finds no Vulkan loader (%s)\n", glfw_error);
        return 1;
    }
    glfwSetWindowUserPointer(a->window, a);
    glfwSetKeyCallback(a->window, on_key);
    glfwSetMouseButtonCallback(a->window, on_mouse_button);
    glfwSetCursorPosCallback(a->window, on_cursor);
    glfwSetFramebufferSizeCallback(a->window, on_framebuffer_size);
    return 0;
}

/* Device with the swapchain extension, instance with GLFW's surface extensions, a surface the queue presents to. */
static int open_device(app *a)
{
    uint32_t ext_count = 0;
    const char **ext = glfwGetRequiredInstanceExtensions(&ext_count);
    if (!ext) {
        fprintf(stderr, "vksky: no Vulkan surface support for this window system (%s)\n", glfw_error);
        return 1;
    }
    gpu_context_desc desc = {.validation = a->o->validate, .device_index = a->o->device_index,
                             .instance_extensions = ext, .instance_extension_count = ext_count,
                             .want_swapchain = true};
    int rc = gpu_context_create(&a->ctx, &desc);
    if (rc != 0) return rc == -2 ? 2 : 1;
    VK_CHECK(glfwCreateWindowSurface(a->ctx.instance, a->window, NULL, &a->surface));
    VkBool32 supported = VK_FALSE;
    VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(a->ctx.physical, a->ctx.queue_family, a->surface, &supported));
    if (!supported) {
        fprintf(stderr, "vksky: the device's queue cannot present to this window; try --device N\n");
        return 1;
    }
    return 0;
}

static int start_rendering(app *a)
{
    const options *o = a->o;
    a->sc.format = choose_format(a);
    if (!swapchain_create(a)) {
        /* Created minimised: start at the requested size; the loop recreates once the window has an area. */
        a->sc.extent = (VkExtent2D){(uint32_t)o->width, (uint32_t)o->height};
        a->swapchain_dirty = true;
    }
    if (o->screenshot && (!a->sc.can_copy || !format_is_rgba8(a->sc.format.format))) {
        fprintf(stderr, "vksky: --screenshot: this surface's images cannot be copied (format %d)\n",
                (int)a->sc.format.format);
        return 1;
    }
    frames_create(a);
    /* The bloom chain is always allocated so B can toggle it; --no-bloom only starts with it off. */
    sky_renderer_desc rdesc = {.width = a->sc.extent.width, .height = a->sc.extent.height, .bloom = true,
                               .readback = false, .external_display = true, .display_format = a->sc.format.format,
                               .render_scale = o->render_scale, .lut = o->lut, .bloom_mips = (uint32_t)o->bloom_mips,
                               .post_pass = o->post_pass, .bloom_downsample = o->bloom_downsample,
                               .bloom_quarter = o->bloom_quarter};
    sky_renderer_create(&a->renderer, &a->ctx, &rdesc);
    sky_renderer_set_atmosphere(&a->renderer, &o->atmosphere, options_sun_radius_rad(o));
    sky_features features = options_features(o);
    sky_renderer_set_features(&a->renderer, &features);
    a->view = o->view;
    camera_init(&a->cam, &o->view);
    camera_to_view(&a->cam, &a->view);
    return 0;
}

static void shut_down(app *a)
{
    if (a->ctx.device) {
        vkDeviceWaitIdle(a->ctx.device);
        if (a->renderer.ctx) sky_renderer_destroy(&a->renderer);
        if (a->frames[0].done) frames_destroy(a);
        swapchain_destroy_views(a, &a->sc);
        if (a->sc.handle) vkDestroySwapchainKHR(a->ctx.device, a->sc.handle, NULL);
    }
    if (a->surface) vkDestroySurfaceKHR(a->ctx.instance, a->surface, NULL);
    if (a->ctx.instance) gpu_context_destroy(&a->ctx);
    if (a->window) glfwDestroyWindow(a->window);
    glfwTerminate();
}

static void print_summary(app *a)
{
    double seconds = glfwGetTime() - a->st.start;
    double gpu = a->st.gpu_samples_total ? a->st.gpu_ms_total / (double)a->st.gpu_samples_total : -1.0;
    printf("frames %ld seconds %.3f fps %.2f gpu_ms %.3f\n", a->presented, seconds,
           seconds > 0 ? (double)a->presented / seconds : 0.0, gpu);
    printf("sun_elevation %.3f\n", a->view.sun_elevation_deg);
    printf("camera altitude_km %.6f yaw %.3f pitch %.3f\n", a->view.altitude_km, a->view.yaw_deg, a->view.pitch_deg);
}

int window_run(const options *o)
{
    char err[512];
    if (o->screenshot && io_check_writable(o->screenshot, err, sizeof err) != 0) {
        fprintf(stderr, "vksky: --screenshot: %s\n", err);
        return 2;
    }
    static app a;   /* static: GLFW callbacks reach it through the window's user pointer */
    a = (app){.o = o};
    const char *test = getenv("VKSKY_TEST_RESIZE");
    a.test.resize = test && strcmp(test, "1") == 0;
    a.test.last_frame = -1;
    int rc = open_window(&a);
    if (rc == 0) rc = open_device(&a);
    if (rc == 0) rc = start_rendering(&a);
    if (rc == 0) {
        gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
        printf("vksky: press F1 for the controls\n");
        fflush(stdout);
        a.st.start = a.st.title_time = a.st.last_frame = glfwGetTime();
        run_loop(&a);
        print_summary(&a);
        rc = a.status;
    }
    shut_down(&a);
    unsigned messages = gpu_validation_message_count();
    if (o->validate && rc != 2) printf("validation_messages %u\n", messages);
    if (messages) {
        fprintf(stderr, "vksky: validation reported %u message%s\n", messages, messages == 1 ? "" : "s");
        if (rc == 0) rc = 1;
    }
    return rc;
}
