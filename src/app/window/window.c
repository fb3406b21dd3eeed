/* Interactive window: GLFW + a Vulkan swapchain, two frames in flight, the fly camera and the lesson's controls.
 *
 * Presentation in one paragraph. Each frame slot (FRAMES_IN_FLIGHT = 2) owns a fence, an "image acquired"
 * semaphore, a command buffer and a timestamp pool; waiting on the slot's fence makes all four reusable. Each
 * swapchain IMAGE owns a "render finished" semaphore: the presentation engine waits on it at some unknown time
 * after vkQueuePresentKHR, and the only moment we know that wait is over is when the same image is acquired
 * again, so the semaphore must follow the image, not the frame slot. The submit waits on the acquire semaphore
 * at COLOR_ATTACHMENT_OUTPUT: the LUT, sky and bloom passes do not touch the swapchain image and may run before
 * the presentation engine lets go of it; the spine's first barrier on the image (usage GPU_USAGE_ACQUIRED, which
 * vksky_frame_swapchain asks for) starts from that same stage, so its layout transition is chained after the wait.
 * The spine ends with the barrier to PRESENT_SRC, and the submit signals the image's semaphore at ALL_COMMANDS so
 * that the tone map's writes, the optional screenshot copy and that layout transition all happen before
 * presentation.
 *
 * Swapchain life: recreated (with oldSwapchain) when the framebuffer size changes, or acquire/present say
 * OUT_OF_DATE or SUBOPTIMAL; no frame is drawn while the window is minimised (we sleep in glfwWaitEvents). The
 * old images' semaphores outlive their presents through VK_EXT_swapchain_maintenance1's present fences where the
 * device has them, else through vkDeviceWaitIdle() (swapchain.c; docs/synchronization.md §6).
 *
 * The window in four files: this one (the loop, frames in flight, screenshot, title, setup), window_api.c (its calls
 * of include/vksky.h: the device adopted, the scene, one vksky_record per frame), swapchain.c (the swapchain's life)
 * and window_input.c (the controls); their shared state is app/window/window_app.h. */
#include "app/runs/startup.h"
#include "app/runs/cpu_time.h"
#include "app/scene/light.h"
#include "app/window/window_app.h"
#include "app/window/window.h"
#include "app/runs/stop.h"
#include "io/atomic_file.h"
#include "io/png_io.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define TITLE_PERIOD_S 0.5
#define STEADY_FROM 10          /* the summary's steady figures start at this presented frame */

/* --- GLFW errors: kept, not printed (no-display runs must print exactly one line) ------------------------- */

static char glfw_error[256];

static void on_glfw_error(int code, const char *text)
{
    snprintf(glfw_error, sizeof glfw_error, "GLFW error 0x%x: %s", code, text ? text : "");
}

/* The framebuffer changed size: the loop recreates the swapchain before its next frame. */
static void on_framebuffer_size(GLFWwindow *w, int width, int height)
{
    (void)width, (void)height;
    app *a = glfwGetWindowUserPointer(w);
    a->swapchain_dirty = true;
}

/* --- Swapchain recreation (swapchain.c) and the renderer's size -------------------------------------------- */

/* Resize, OUT_OF_DATE or SUBOPTIMAL: a new swapchain and a renderer of the new size. Waiting for the device
 * first keeps it simple: nothing in flight still uses the old swapchain or the old-size render targets. */
static void swapchain_recreate(app *a)
{
    VK_CHECK(vkDeviceWaitIdle(a->ctx.device));
    if (!swapchain_create(&a->sc, &a->ctx, a->surface, a->window, a->test.resize || a->test.report)) {
        /* The surface has no area yet (minimised, or the resize still on its way): stay dirty, don't spin. */
        glfwWaitEventsTimeout(0.05);
        return;
    }
    window_api_check(vksky_renderer_resize(a->renderer, a->sc.extent.width, a->sc.extent.height),
                     "vksky_renderer_resize");
    a->swapchain_dirty = false;
    a->test.present_due = a->test.report;
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
        vkFreeCommandBuffers(a->ctx.device, a->ctx.command_pool, 1, &f->cmd);
    }
}

/* After the slot's fence: its timestamps are final (vksky_frame_timer: the slot's timer, read once). The frame's GPU
 * time is the sum of its passes. */
static void read_timer(app *a)
{
    vksky_pass_timing t[32];
    uint32_t n = 0;
    double sum = 0.0;
    if (vksky_renderer_get_slot_timings(a->renderer, a->slot, t, 32, &n) != VKSKY_SUCCESS || n == 0) return;
    for (uint32_t i = 0; i < n && i < 32; ++i) sum += t[i].gpu_ms;
    a->st.gpu_ms_sum += sum, a->st.gpu_samples++;
    a->st.gpu_ms_total += sum, a->st.gpu_samples_total++;
}

/* Record the frame into the slot's command buffer through vksky_record: the frame's values as extension structs
 * (app/window/window_api.c), the spine ending on the PRESENT barrier. */
static void record(app *a, frame_slot *f, uint32_t image, bool capture)
{
    VK_CHECK(vkResetCommandBuffer(f->cmd, 0));
    VkCommandBufferBeginInfo binfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(f->cmd, &binfo));
    /* The renderer's own images (HDR, bloom mips, LUTs) are shared by both frames in flight. That is safe
     * without per-frame copies: both frames go to one queue, and a pipeline barrier's source scope covers
     * every command submitted before it on that queue, earlier submissions included. So the spine's first
     * barrier on the HDR image in frame N+1 (WAR against the "fragment sampled" reads) waits for frame N's
     * bloom and tone map reads, even though frame N was a different vkQueueSubmit2. Frames in flight overlap
     * CPU recording with GPU work; on the GPU they run one after the other. */
    /* --trace-barriers prints the first frame; VKSKY_TRACE_CAPTURE=1 the screenshot's frame too, whose host-read
     * barrier (capture.to_host) ctest host_read_barriers checks (the guide's tables keep the first frame only). */
    const char *tc = getenv("VKSKY_TRACE_CAPTURE");
    bool trace = a->o->trace_barriers && (!a->traced || (capture && tc && !strcmp(tc, "1")));
    window_api_trace(a, trace);
    /* --async-luts: the LUT passes (when stale) go to the compute queue first; submit() makes this frame wait for
     * them. A LUT build happens at the first frame, or after F5 or a resize waited for the device. */
    f->luts_wait = false;
    if (a->async.device && host_async_luts(&a->async, a->renderer, false, &f->luts_wait)) exit(1);
    window_api_record(a, f->cmd, image, capture);
    if (trace) a->traced = true;
    window_api_trace(a, false);
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
    /* --async-luts: also wait for this frame's LUT build (if any) and count the frame on graphics_done, which the
     * next LUT build waits for (docs/synchronization.md §10). */
    VkSemaphoreSubmitInfo waits[2] = {wait}, signals[2] = {signal};
    uint32_t wait_count = 1, signal_count = 1;
    if (a->async.device)
        wait_count += host_async_frame(&a->async, f->luts_wait, &waits[1], &signals[1]), signal_count = 2;
    VkSubmitInfo2 info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = wait_count,
                          .pWaitSemaphoreInfos = waits, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cmd,
                          .signalSemaphoreInfoCount = signal_count, .pSignalSemaphoreInfos = signals};
    /* Reset only now that a submit follows for sure: a reset fence nobody signals would hang the next wait. */
    VK_CHECK(vkResetFences(a->ctx.device, 1, &f->done));
    VK_CHECK(vkQueueSubmit2(a->ctx.queue, 1, &info, f->done));
}

/* Returns whether the image went to the presentation engine (OUT_OF_DATE: it did not). */
static bool present(app *a, uint32_t image)
{
    /* With VK_EXT_swapchain_maintenance1, a fence that signals once the presentation engine no longer waits
     * on the semaphore: what swapchain.c waits for before destroying it (docs/synchronization.md §6). */
    VkFence fence = swapchain_present_fence(&a->sc, &a->ctx, image);
    VkSwapchainPresentFenceInfoEXT fence_info = {.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_PRESENT_FENCE_INFO_EXT,
                                                 .swapchainCount = 1, .pFences = &fence};
    VkPresentInfoKHR info = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, .pNext = fence ? &fence_info : NULL,
                             .waitSemaphoreCount = 1,
                             .pWaitSemaphores = &a->sc.render_finished[image], .swapchainCount = 1,
                             .pSwapchains = &a->sc.handle, .pImageIndices = &image};
    VkResult r = vkQueuePresentKHR(a->ctx.queue, &info);
    /* Even when rejected as OUT_OF_DATE the present's semaphore wait still executes; recreate next loop. */
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) a->swapchain_dirty = true;
    else VK_CHECK(r);
    return r != VK_ERROR_OUT_OF_DATE_KHR;
}

/* One frame: wait for the slot, acquire, record, submit, present. Returns false when nothing was submitted
 * (acquire said OUT_OF_DATE: no image, no semaphore signal, the fence left signalled for the retry). */
static bool draw_frame(app *a, bool capture)
{
    frame_slot *f = &a->frames[a->slot];
    /* The slot's previous submission is done: its command buffer, semaphore and timestamps are free. */
    VK_CHECK(vkWaitForFences(a->ctx.device, 1, &f->done, VK_TRUE, UINT64_MAX));
    read_timer(a);
    /* Its meter's result (a frame or two late): the EV100 the title shows and the +/- keys step from. A slot never
     * metered counts no pixels. */
    vksky_exposure m = {0};
    if (vksky_renderer_get_exposure(a->renderer, a->slot, &m) == VKSKY_SUCCESS && a->auto_exposure &&
        m.pixel_count > 0.0)
        a->view.exposure_ev = a->view.ev100 ? m.ev100 : -log2(1.2) - m.ev100;
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
    if (present(a, image) && a->test.present_due) {
        printf("presented %ux%u\n", a->sc.extent.width, a->sc.extent.height);
        a->test.present_due = false;
    }
    a->slot = (a->slot + 1) % FRAMES_IN_FLIGHT;
    a->presented++;
    if (a->presented == STEADY_FROM) a->st.steady_time = glfwGetTime(), a->st.steady_cpu_ms = process_cpu_ms();
    return true;
}

/* --- Screenshot -------------------------------------------------------------------------------------------- */

static bool format_is_bgra(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM; }

static bool format_is_rgba8(VkFormat f)
{
    return format_is_bgra(f) || f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_R8G8B8A8_UNORM ||
           f == VK_FORMAT_A8B8G8R8_SRGB_PACK32 || f == VK_FORMAT_A8B8G8R8_UNORM_PACK32;
}

/* The last frame again, with the spine copying the swapchain image into the renderer's capture buffer
 * (vksky_frame_capture); after its fence the pixels are written as PNG. Both sRGB and UNORM swapchains hold
 * sRGB-encoded bytes (the tone map encodes for UNORM), so the PNG is tagged sRGB either way. Returns false if the
 * frame could not be drawn yet. */
static bool draw_screenshot_frame(app *a)
{
    VkExtent2D e = a->sc.extent;
    frame_slot *f = &a->frames[a->slot];
    if (!draw_frame(a, true)) return false;
    VK_CHECK(vkWaitForFences(a->ctx.device, 1, &f->done, VK_TRUE, UINT64_MAX));
    vksky_readback shot;
    window_api_check(vksky_renderer_get_capture(a->renderer, &shot), "vksky_renderer_get_capture");
    size_t bytes = (size_t)e.width * e.height * 4;
    uint8_t *px = malloc(bytes);
    if (!px) {
        fprintf(stderr, "vksky: --screenshot: out of memory\n");
        a->status = 1;
        return true;
    }
    memcpy(px, shot.display_rgba8, bytes);
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
    free(px);
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
    char title[240];
    int n = snprintf(title, sizeof title, "vksky | %.1f fps | GPU %.2f ms | sun %.1f\xc2\xb0 | altitude %.*f %s", fps,
                     gpu, a->view.sun_elevation_deg, h < 1.0 ? 1 : 3, h < 1.0 ? h * 1000.0 : h, h < 1.0 ? "m" : "km");
    if (a->view.ev100 && n > 0 && (size_t)n < sizeof title) {
        /* Photometric units: the exposure as EV100 (auto: the GPU meter's, read back in draw_frame) and the sky's
         * luminance under the cursor (the CPU reference; the view's centre while the mouse looks around). */
        int w = (int)a->sc.extent.width, hh = (int)a->sc.extent.height;
        double cx = a->in.captured ? 0.5 * w : a->in.cursor_x, cy = a->in.captured ? 0.5 * hh : a->in.cursor_y;
        double cd = light_meter_pixel(a->o, &a->view, w, hh, cx, cy);
        snprintf(title + n, sizeof title - (size_t)n, " | EV100 %.1f%s | %.4g cd/m\xc2\xb2 at the cursor",
                 a->view.exposure_ev, a->auto_exposure ? " auto" : "", cd);
    }
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

/* VKSKY_TEST_F5=N:FILE: at presented frame N, wait (events still polled, at most 60 s) until FILE exists, the test's
 * word that it changed the scene file on disk, then press F5 from inside (window_input_reload): no keyboard focus
 * or window manager needed, and the frames before and after the change are known. */
static void test_f5(app *a)
{
    if (!a->test.f5_file || a->presented != a->test.f5_frame) return;
    printf("test: F5 at frame %ld waits for %s\n", a->presented, a->test.f5_file);
    fflush(stdout);
    for (int i = 0; i < 1200 && !stop_requested() && access(a->test.f5_file, F_OK) != 0; ++i) glfwWaitEventsTimeout(0.05);
    a->test.f5_file = NULL;
    window_input_reload(a);
}

/* Nothing to present to: an iconified or unmapped window, or a 0x0 framebuffer (minimised on some platforms). */
static bool window_minimized(app *a)
{
    int w, h;
    glfwGetFramebufferSize(a->window, &w, &h);
    return w == 0 || h == 0 || glfwGetWindowAttrib(a->window, GLFW_ICONIFIED) ||
           !glfwGetWindowAttrib(a->window, GLFW_VISIBLE);
}

/* Sleep in the event queue until the window is back (no spinning). The test hook restores it itself. The wait has
 * a timeout because GLFW's untimed wait retries when a signal interrupts it: the graceful stop (stop.h) is seen
 * within STOP_POLL_S. */
#define STOP_POLL_S 0.25
static void wait_while_minimized(app *a)
{
    while (!glfwWindowShouldClose(a->window) && !stop_requested() && window_minimized(a)) {
        if (!a->test.minimized_waits) {
            glfwWaitEventsTimeout(STOP_POLL_S);
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
        if (stop_requested()) break;   /* SIGINT/SIGTERM: no further frame, no screenshot; shut_down waits idle */
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
        /* Auto exposure eases toward the meter like an eye (docs/units.md): time constant EXPOSURE_TAU_S. */
        a->exposure_ease = 1.0 - exp(-dt / EXPOSURE_TAU_S);
        window_input_read(a, dt);
        bool last = quitting || (o->frames && a->presented + 1 == o->frames);
        if (last && o->screenshot) {
            if (draw_screenshot_frame(a)) break;
            continue;
        }
        if (draw_frame(a, false)) update_title(a, now);
        test_hook(a);
        test_f5(a);
    }
}

/* --- Setup and teardown ------------------------------------------------------------------------------------ */

/* No X server / compositor (or one that refuses us): one line, exit 2, like any other unusable input. GLFW's own
 * reason goes in it: "unset" and "set but refused" (a server that went away, a full client table) are different
 * faults to a user, and a test that meets this line under Xvfb needs to know which. */
static int no_display(void)
{
    fprintf(stderr, "vksky: no display available (DISPLAY/WAYLAND_DISPLAY unset or unusable%s%s); use --render "
            "FILE.exr|FILE.png for headless rendering\n", glfw_error[0] ? ": " : "", glfw_error);
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
    window_input_install(a);
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
    /* --async-luts; VKSKY_ASYNC_ONE_QUEUE=1 (tests): on a one-queue device, both submissions on that queue. */
    const char *one_queue = getenv("VKSKY_ASYNC_ONE_QUEUE");
    if (a->o->async_luts)
        desc.async_compute = one_queue && !strcmp(one_queue, "1") ? GPU_ASYNC_ONE_QUEUE : GPU_ASYNC_ON;
    int rc = gpu_context_create(&a->ctx, &desc);
    if (rc != 0) return rc == -2 ? 2 : 1;
    startup_open_cache(&a->ctx, a->o);
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
    a->sc.format = swapchain_choose_format(&a->ctx, a->surface);
    if (!swapchain_create(&a->sc, &a->ctx, a->surface, a->window, a->test.resize || a->test.report)) {
        /* Created minimised: start at the requested size; the loop recreates once the window has an area. */
        a->sc.extent = (VkExtent2D){(uint32_t)o->width, (uint32_t)o->height};
        a->swapchain_dirty = true;
    }
    a->test.present_due = a->test.report;
    if (o->screenshot && (!a->sc.can_copy || !format_is_rgba8(a->sc.format.format))) {
        fprintf(stderr, "vksky: --screenshot: this surface's images cannot be copied (format %d)\n",
                (int)a->sc.format.format);
        return 1;
    }
    frames_create(a);
    /* The device adopted by a vksky context, the command line's scene, the renderer (app/window/window_api.c). */
    int rc = window_api_open(a);
    if (rc != 0) return rc;
    a->view = o->view;
    /* Photometric units without --exposure: auto exposure, metered on the GPU in every frame (the first included). */
    a->auto_exposure = o->view.ev100 && (o->auto_exposure || !o->exposure_given);
    camera_init(&a->cam, &o->view, o->atmosphere.bottom_radius);
    camera_to_view(&a->cam, &a->view);
    return 0;
}

static void shut_down(app *a)
{
    if (a->ctx.device) {
        vkDeviceWaitIdle(a->ctx.device);
        window_api_close(a);
        if (a->frames[0].done) frames_destroy(a);
        swapchain_destroy(&a->sc, &a->ctx);
    }
    if (a->surface) vkDestroySurfaceKHR(a->ctx.instance, a->surface, NULL);
    if (a->ctx.device) startup_close_cache(&a->ctx);
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
    /* From the STEADY_FROM-th frame on: no shader compilation, LUT builds or first-frame setup in the figures. */
    long steady = a->presented - STEADY_FROM;
    if (steady > 0) {
        double s = glfwGetTime() - a->st.steady_time;
        printf("steady_frames %ld fps %.2f cpu_ms %.3f\n", steady, s > 0 ? (double)steady / s : 0.0,
               (process_cpu_ms() - a->st.steady_cpu_ms) / (double)steady);
    }
    printf("sun_elevation %.3f\n", a->view.sun_elevation_deg);
    printf("camera altitude_km %.6f yaw %.3f pitch %.3f\n", a->view.altitude_km, a->view.yaw_deg, a->view.pitch_deg);
    printf("swapchain_format %d\n", (int)a->sc.format.format);   /* VkFormat: 50/44 B8G8R8A8 SRGB/UNORM (window_dither) */
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
    a.test.report = (test = getenv("VKSKY_TEST_REPORT")) && strcmp(test, "1") == 0;
    stop_install();
    a.test.last_frame = -1;
    if ((test = getenv("VKSKY_TEST_F5")) && *test) {
        char *colon = NULL;
        a.test.f5_frame = strtol(test, &colon, 10);
        if (colon == test || *colon != ':' || !colon[1] || a.test.f5_frame < 1) {
            fprintf(stderr, "vksky: VKSKY_TEST_F5: '%s'; expected N:FILE (a frame number >= 1, a file to wait for)\n",
                    test);
            return 2;
        }
        a.test.f5_file = colon + 1;
    }
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "vksky: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
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
    return stop_status(rc);
}
